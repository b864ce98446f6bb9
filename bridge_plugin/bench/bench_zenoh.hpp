// How the benches' own Zenoh sessions meet the peers they start: the plugin's ZenohTransport
// options for one endpoint. The benches run from the build tree, where the package's installed
// default config is not: on zenoh-c they name its source copy (zenoh-pico takes no file).
#pragma once

#include <string>

#include "nav2_pyif_bridge/zenoh_transport.hpp"

namespace nav2_pyif_bench
{

inline nav2_pyif_bridge::ZenohOptions connect_to(const std::string & endpoint)
{
  nav2_pyif_bridge::ZenohOptions options;
  options.connect = {endpoint};
#if !defined(ZENOHCXX_ZENOHPICO)
  options.config_file = NAV2_PYIF_BENCH_ZENOH_CONFIG;
#endif
  return options;
}

}  // namespace nav2_pyif_bench
