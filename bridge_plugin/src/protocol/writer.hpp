// The canonical msgpack primitives (PROTOCOL.md section 2), on top of msgpack::packer.
// encode.cpp says *what* to write, in schema order; this says *how*: floats always float64,
// ints in their shortest form, text as str, bytes as bin.
#pragma once

#include <msgpack.hpp>

#include <cstddef>
#include <cstdint>
#include <string_view>
#include <utility>
#include <vector>

#include "field_path.hpp"

namespace nav2_pyif_bridge::protocol::detail
{

class Writer
{
public:
  // capacity_hint: bytes to reserve up front (a costmap is large; most messages are not).
  explicit Writer(std::size_t capacity_hint);
  Writer(const Writer &) = delete;
  Writer & operator=(const Writer &) = delete;

  void map(std::size_t entries);
  void array(std::size_t elements);
  // Map keys are the schema's ASCII literals, so they skip the UTF-8 check of str().
  void key(std::string_view name);
  // Throws EncodeError naming `where` when the text is not UTF-8.
  void str(std::string_view text, const FieldPath & where);
  void i64(std::int64_t value);
  void u64(std::uint64_t value);
  void f64(double value);
  void boolean(bool value);
  void bin(const std::uint8_t * data, std::size_t size);
  // A packed little-endian float64 array as one `bin` (paths, footprints).
  void packed_f64(const std::vector<double> & values);

  std::vector<std::uint8_t> take() {return std::move(out_);}

private:
  // msgpack::packer writes through any type with write(const char *, size_t).
  struct Sink
  {
    std::vector<std::uint8_t> & out;
    void write(const char * data, std::size_t size)
    {
      out.insert(out.end(), data, data + size);
    }
  };

  std::vector<std::uint8_t> out_;
  Sink sink_{out_};
  msgpack::packer<Sink> packer_{sink_};
};

}  // namespace nav2_pyif_bridge::protocol::detail
