#pragma once

#include <filesystem>
#include <string>

// Outputs are checked before a command does its work (a simulation may take minutes): each
// throws bipednav::Error naming `flag` (exit 2) when the output cannot be written.
namespace bipednav::app {

// Creates the directory (with its parents) and writes and removes a probe file in it.
void prepare_output_dir(const std::filesystem::path& dir, const std::string& flag);
// Creates the file's directory (with its parents) and checks that the file can be opened for
// writing, leaving an existing file as it was and no file where there was none.
void prepare_output_file(const std::filesystem::path& file, const std::string& flag);

}  // namespace bipednav::app
