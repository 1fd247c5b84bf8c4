// SPDX-License-Identifier: BSD-3-Clause
// The examples' output folder: created with its parents, or an error naming the folder and the
// reason (a file in its place, no permission), which main() prints as one line.
#pragma once

#include <filesystem>
#include <string>
#include <system_error>

#include "mpsfsi/core/error.hpp"

namespace mpsfsi_examples {

inline void make_output_folder(const std::string& folder) {
  std::error_code error;
  std::filesystem::create_directories(folder, error);
  if (!error && !std::filesystem::is_directory(folder, error))
    error = std::make_error_code(std::errc::not_a_directory);
  if (error)
    throw mpsfsi::InvalidInput("--out: cannot create the output folder '" + folder + "': " + error.message());
}

}  // namespace mpsfsi_examples
