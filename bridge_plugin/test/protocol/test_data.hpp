// The shared vectors (protocol/vectors): where they are and how to read them.
#pragma once

#include <nlohmann/json.hpp>

#include <cstdint>
#include <filesystem>
#include <ostream>
#include <string>
#include <vector>

namespace nav2_pyif_bridge::protocol::test
{

using Json = nlohmann::ordered_json;  // ordered: key order is part of the canonical form

struct VectorEntry
{
  std::string name;
  std::string kind;  // "request" or "reply"
  std::string op;
  std::string description;
};

// Test names show the vector's name, not a byte dump of the struct.
inline void PrintTo(const VectorEntry & entry, std::ostream * os) {*os << entry.name;}

// $NAV2_PYIF_VECTORS_DIR when set, else the directory CMake compiled in.
std::filesystem::path vectors_dir();

// index.json's entries. Throws std::runtime_error naming the file when it cannot be read.
std::vector<VectorEntry> load_index();

std::vector<std::uint8_t> read_vector_bytes(const std::string & name);  // <name>.msgpack
Json read_vector_json(const std::string & name);                        // <name>.json

}  // namespace nav2_pyif_bridge::protocol::test
