// libFuzzer harness: key parsing. The bytes are a key prefix as a plugin's `key` parameter
// gives it (validate_prefix, KeySpace) and a liveliness token key (KeySpace::host_id_of).
// Seeds: the prefixes of protocol/vectors/keys.json (written at configure time).
#include <cstddef>
#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>

#include "fuzz_check.hpp"
#include "nav2_pyif_bridge/client/keys.hpp"

namespace protocol = nav2_pyif_bridge::protocol;
namespace client = nav2_pyif_bridge::client;
using nav2_pyif_bridge::fuzz::broken;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t * data, std::size_t size)
{
  const std::string text(reinterpret_cast<const char *>(data), size);

  const std::string_view id = client::KeySpace::host_id_of(text);
  if (id.find('/') != std::string_view::npos || text.size() < id.size() ||
    text.compare(text.size() - id.size(), id.size(), id) != 0)
  {
    broken("host_id_of is not the last chunk of the token key");
  }

  std::optional<client::KeySpace> keys;
  try {
    keys.emplace(text);
  } catch (const std::invalid_argument &) {
    return 0;  // refused, naming the prefix
  }
  // Every key built under an accepted prefix is itself a valid key below it.
  for (std::size_t i = 0; i < protocol::kOpCount; ++i) {
    const std::string call = keys->call(static_cast<protocol::Op>(i));
    if (call.rfind(text + "/", 0) != 0) {
      broken("the call key '" + call + "' is not under its prefix");
    }
    try {
      client::validate_prefix(call);
    } catch (const std::invalid_argument & error) {
      broken("the call key '" + call + "' is no valid key: " + error.what());
    }
  }
  if (client::KeySpace::host_id_of(text + "/host/h1") != "h1") {
    broken("host_id_of misreads a token key under '" + text + "'");
  }
  return 0;
}
