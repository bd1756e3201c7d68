#pragma once
// An HDF5 file held in memory (received over a network, or the input of a fuzz target): the readers of every
// format accept it in place of a path and apply the same checks, without touching the disk.
#include <cstddef>
#include <string>

namespace centaur::data {

struct FileImage {
  const void* data = nullptr;
  std::size_t size = 0;
  std::string label = "<memory>";  ///< names the image in messages, as a path would
};

}  // namespace centaur::data
