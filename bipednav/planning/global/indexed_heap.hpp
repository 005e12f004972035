#pragma once

#include <cstdint>
#include <vector>

namespace bipednav::planning::global {

// A two-part priority compared lexicographically ([k1, k2] of D* Lite, eqs. 5.2-5.3).
struct Key {
  std::int64_t k1 = 0;
  std::int64_t k2 = 0;
  bool operator<(const Key& o) const { return k1 < o.k1 || (k1 == o.k1 && k2 < o.k2); }
  bool operator==(const Key& o) const = default;
};

// Binary min-heap over vertex indices [0, n) with a position table, so a vertex's key can be
// updated or the vertex removed in O(log n) (the U.Update / U.Remove of Algorithm 3).
class IndexedHeap {
 public:
  void resize(std::size_t n) {
    clear();
    pos_.assign(n, -1);
  }
  void clear() {
    for (const auto& e : heap_) pos_[e.v] = -1;
    heap_.clear();
  }
  bool empty() const { return heap_.empty(); }
  std::size_t capacity() const { return pos_.size(); }
  std::size_t size() const { return heap_.size(); }
  bool contains(std::size_t v) const { return pos_[v] >= 0; }
  std::uint32_t top() const { return heap_.front().v; }
  Key top_key() const { return heap_.front().key; }

  void insert(std::size_t v, const Key& key) {
    heap_.push_back({key, static_cast<std::uint32_t>(v)});
    pos_[v] = static_cast<std::int32_t>(heap_.size() - 1);
    sift_up(heap_.size() - 1);
  }
  void update(std::size_t v, const Key& key) {
    const std::size_t i = static_cast<std::size_t>(pos_[v]);
    const Key old = heap_[i].key;
    heap_[i].key = key;
    if (key < old)
      sift_up(i);
    else
      sift_down(i);
  }
  // Inserts or updates.
  void push(std::size_t v, const Key& key) { contains(v) ? update(v, key) : insert(v, key); }
  void remove(std::size_t v) {
    const std::size_t i = static_cast<std::size_t>(pos_[v]);
    pos_[v] = -1;
    const std::size_t last = heap_.size() - 1;
    if (i != last) {
      heap_[i] = heap_[last];
      pos_[heap_[i].v] = static_cast<std::int32_t>(i);
      heap_.pop_back();
      sift_down(i);
      sift_up(i);
    } else {
      heap_.pop_back();
    }
  }
  std::uint32_t pop() {
    const std::uint32_t v = top();
    remove(v);
    return v;
  }

 private:
  struct Entry {
    Key key;
    std::uint32_t v;
  };
  void place(std::size_t i, const Entry& e) {
    heap_[i] = e;
    pos_[e.v] = static_cast<std::int32_t>(i);
  }
  void sift_up(std::size_t i) {
    const Entry e = heap_[i];
    while (i > 0) {
      const std::size_t p = (i - 1) / 2;
      if (!(e.key < heap_[p].key)) break;
      place(i, heap_[p]);
      i = p;
    }
    place(i, e);
  }
  void sift_down(std::size_t i) {
    const Entry e = heap_[i];
    const std::size_t n = heap_.size();
    for (;;) {
      std::size_t c = 2 * i + 1;
      if (c >= n) break;
      if (c + 1 < n && heap_[c + 1].key < heap_[c].key) ++c;
      if (!(heap_[c].key < e.key)) break;
      place(i, heap_[c]);
      i = c;
    }
    place(i, e);
  }

  std::vector<Entry> heap_;
  std::vector<std::int32_t> pos_;
};

}  // namespace bipednav::planning::global
