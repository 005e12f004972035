#include "ros/bag_sweeps.hpp"

#include <rosbag/bag.h>
#include <rosbag/view.h>

#include <memory>
#include <set>

#include "bipednav/common/error.hpp"
#include "ros/conversions.hpp"

namespace bipednav::ros1 {

namespace {

// The open bag and the selected messages (the instances refer to the bag and its view).
struct BagMessages {
  rosbag::Bag bag;
  std::unique_ptr<rosbag::View> view;
  std::vector<rosbag::MessageInstance> messages;
};

std::string pointcloud_topic(const rosbag::Bag& bag, const std::string& name) {
  std::set<std::string> topics;
  rosbag::View all(bag);
  for (const rosbag::ConnectionInfo* c : all.getConnections())
    if (c->datatype == "sensor_msgs/PointCloud2") topics.insert(c->topic);
  std::string list;
  for (const auto& t : topics) list += (list.empty() ? "" : ", ") + t;
  if (topics.size() != 1)
    throw FileError(name, "",
                    topics.empty() ? "no sensor_msgs/PointCloud2 topic"
                                   : "several PointCloud2 topics (" + list + "): choose one with --topic");
  return *topics.begin();
}

}  // namespace

runner::SweepSequence open_bag_sweeps(const std::filesystem::path& file, const std::string& topic) {
  auto b = std::make_shared<BagMessages>();
  try {
    b->bag.open(file.string(), rosbag::bagmode::Read);
  } catch (const std::exception& e) {
    throw FileError(file.string(), "", std::string("cannot open the bag: ") + e.what());
  }
  const std::string t = topic.empty() ? pointcloud_topic(b->bag, file.string()) : topic;
  b->view = std::make_unique<rosbag::View>(b->bag, rosbag::TopicQuery(t));
  for (const rosbag::MessageInstance& m : *b->view) {
    if (m.getDataType() != "sensor_msgs/PointCloud2")
      throw FileError(file.string(), "topic " + t, "expected sensor_msgs/PointCloud2, got " + m.getDataType());
    b->messages.push_back(m);
  }
  if (b->messages.empty()) throw FileError(file.string(), "topic " + t, "no messages");
  runner::SweepSequence s;
  s.format = "rosbag";
  s.count = b->messages.size();
  s.read = [b, name = file.string(), t](std::size_t i) {
    const auto msg = b->messages.at(i).instantiate<sensor_msgs::PointCloud2>();
    if (!msg) throw FileError(name, "topic " + t + ", message " + std::to_string(i + 1), "not a PointCloud2");
    return from_msg(*msg);
  };
  return s;
}

void write_bag_sweeps(const std::filesystem::path& file, const std::string& topic,
                      const std::vector<PointCloud>& sweeps) {
  ros::Time::init();  // rosbag stamps need the time system, no master
  rosbag::Bag bag;
  try {
    bag.open(file.string(), rosbag::bagmode::Write);
  } catch (const std::exception& e) {
    throw FileError(file.string(), "", std::string("cannot open the bag for writing: ") + e.what());
  }
  for (std::size_t i = 0; i < sweeps.size(); ++i) {
    PointCloud c = sweeps[i];
    if (c.stamp_s <= 0.0) c.stamp_s = 0.1 * static_cast<double>(i + 1);
    bag.write(topic, to_time(c.stamp_s), to_msg(c));
  }
  bag.close();
}

}  // namespace bipednav::ros1
