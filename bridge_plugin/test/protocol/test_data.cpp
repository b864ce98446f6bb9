#include "test_data.hpp"

#include <cstdlib>
#include <fstream>
#include <iterator>
#include <stdexcept>

namespace nav2_pyif_bridge::protocol::test
{
namespace
{

std::string read_file(const std::filesystem::path & path)
{
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    throw std::runtime_error("cannot read " + path.string() +
            " (set NAV2_PYIF_VECTORS_DIR to the protocol/vectors directory)");
  }
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

}  // namespace

std::filesystem::path vectors_dir()
{
  if (const char * from_env = std::getenv("NAV2_PYIF_VECTORS_DIR")) {
    if (*from_env != '\0') {
      return from_env;
    }
  }
#ifdef NAV2_PYIF_VECTORS_DIR
  return NAV2_PYIF_VECTORS_DIR;
#else
  return "protocol/vectors";
#endif
}

std::vector<VectorEntry> load_index()
{
  const Json index = Json::parse(read_file(vectors_dir() / "index.json"));
  std::vector<VectorEntry> out;
  for (const auto & entry : index.at("vectors")) {
    out.push_back({entry.at("name").get<std::string>(), entry.at("kind").get<std::string>(),
        entry.at("op").get<std::string>(), entry.at("description").get<std::string>()});
  }
  return out;
}

std::vector<std::uint8_t> read_vector_bytes(const std::string & name)
{
  const std::string data = read_file(vectors_dir() / (name + ".msgpack"));
  return std::vector<std::uint8_t>(data.begin(), data.end());
}

Json read_vector_json(const std::string & name)
{
  return Json::parse(read_file(vectors_dir() / (name + ".json")));
}

}  // namespace nav2_pyif_bridge::protocol::test
