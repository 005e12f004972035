#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace bipednav::io {

// A Moving AI Lab grid map (Sturtevant 2012): tiles row by row, (0, 0) = top-left, x = column,
// y = row. '.', 'G' and 'S' are passable, every other tile is blocked.
struct MovingAiMap {
  std::string name;
  int width = 0;
  int height = 0;
  std::vector<char> tiles;  // row-major, height * width

  char tile(int x, int y) const { return tiles[static_cast<std::size_t>(y) * width + x]; }
  bool passable(int x, int y) const;
};

bool movingai_passable(char tile);

// One problem of a .scen file (version 1).
struct MovingAiProblem {
  int bucket = 0;
  std::string map;
  int map_width = 0;
  int map_height = 0;
  int start_x = 0;
  int start_y = 0;
  int goal_x = 0;
  int goal_y = 0;
  double optimal_length = 0.0;  // octile, diagonal sqrt 2, no corner cutting
};

// Both readers raise FileError naming the file, the line and the field on malformed input.
MovingAiMap read_movingai_map(const std::filesystem::path& file);
std::vector<MovingAiProblem> read_movingai_scen(const std::filesystem::path& file);

// The same, from text (`name` stands for the file in messages).
MovingAiMap parse_movingai_map(const std::string& text, const std::string& name);
std::vector<MovingAiProblem> parse_movingai_scen(const std::string& text, const std::string& name);

}  // namespace bipednav::io
