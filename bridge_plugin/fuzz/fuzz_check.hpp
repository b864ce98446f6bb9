// What the harnesses share: how a broken property stops the fuzzer, and the round-trip
// property of the codec. A harness may let a documented exception (DecodeError, ...) end an
// input quietly; anything else (a crash, a sanitizer report, a broken property) is a finding.
#pragma once

#include <cstdio>
#include <cstdlib>
#include <string>

#include "nav2_pyif_bridge/protocol/codec.hpp"

namespace nav2_pyif_bridge::fuzz
{

// Stops the run with a message: libFuzzer saves the input as crash-<sha1>.
[[noreturn]] inline void broken(const std::string & property)
{
  std::fprintf(stderr, "nav2_pyif fuzz: property broken: %s\n", property.c_str());
  std::abort();
}

// A decoded message is canonical once re-encoded: encoding it works (the decoder accepted
// nothing the encoder refuses), the bytes decode again, and re-encode to the same bytes.
// `encode` and `decode` are the codec's pair for one message kind (and op).
template<class Message, class Encode, class Decode>
void expect_round_trip(const Message & decoded, Encode encode, Decode decode, const char * what)
{
  protocol::Bytes first;
  try {
    first = encode(decoded);
  } catch (const protocol::EncodeError & error) {
    broken(std::string(what) + " decoded, but its encoding fails: " + error.what());
  }
  protocol::Bytes second;
  try {
    second = encode(decode(first));
  } catch (const std::exception & error) {
    broken(std::string(what) + " re-encoded does not decode again: " + error.what());
  }
  if (first != second) {
    broken(std::string(what) + " re-encoded is not canonical: two encodings differ");
  }
}

}  // namespace nav2_pyif_bridge::fuzz
