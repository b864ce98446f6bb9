// The JSON form of a msgpack tree (PROTOCOL.md section 11), for comparing decoded messages
// with the vectors' expected .json files, and for building malformed messages in tests.
//
// Conventions: bin as {"$bin": "<hex>"}, or {"$bin_len": n, "$bin_crc32": c} above 4 KiB;
// non-finite floats as {"$float": "nan" | "inf" | "-inf"}; ints as JSON integers, floats as
// JSON floats (the comparison keeps them apart).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "nav2_pyif_bridge/protocol/messages.hpp"
#include "test_data.hpp"

namespace nav2_pyif_bridge::protocol::test
{

// A decoded message as the tree its canonical encoding would have, built from the typed
// structs field by field (through the generated for_each_field, not the encoder, which the
// byte comparison tests).
Json to_json(const Request & request);
Json to_json(const Reply & reply);

// "" when the trees are equal: same keys in the same order, ints equal to ints, floats
// bit-equal to floats (so -0.0 differs from 0.0). Otherwise where and how they differ first.
std::string first_difference(const Json & expected, const Json & actual);

// A JSON tree -> msgpack bytes: ints in their shortest form, floats as float64, {"$bin": hex}
// as bin, {"$float": ...} as a non-finite float64, {"$float32": x} as a float32.
std::vector<std::uint8_t> pack_json(const Json & tree);

}  // namespace nav2_pyif_bridge::protocol::test
