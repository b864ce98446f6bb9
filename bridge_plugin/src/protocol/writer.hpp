// The canonical msgpack primitives (PROTOCOL.md section 2), on top of msgpack-c's
// msgpack_packer (the C library the rosdep key `msgpack` installs on every platform).
// The generated body_codec.cpp says *what* to write, in schema order; this says *how*, once
// per field kind: floats always float64, ints in their shortest form, text as str, bytes as
// bin.
#pragma once

#include <msgpack.h>

#include <array>
#include <cstddef>
#include <cstdint>
#include <initializer_list>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "field_path.hpp"
#include "nav2_pyif_bridge/protocol/params.hpp"

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
  // Map keys (and op names) are the schema's ASCII literals, so they skip the UTF-8 check of
  // str().
  void key(std::string_view name);
  // Throws EncodeError naming `where` when the text is not UTF-8.
  void str(std::string_view text, const FieldPath & where);
  void i64(std::int64_t value);
  void u64(std::uint64_t value);
  void f64(double value);
  void boolean(bool value);
  void bin(const std::uint8_t * data, std::size_t size);
  void bin(const std::vector<std::uint8_t> & bytes) {bin(bytes.data(), bytes.size());}
  // A packed little-endian float64 array as one `bin` (paths, footprints): whole rows of
  // row_size values, else EncodeError naming `where`.
  void rows(const std::vector<double> & values, std::size_t row_size, const FieldPath & where);
  // A msgpack array of N float64 (float[6], float[7]).
  template<std::size_t N>
  void floats(const std::array<double, N> & values)
  {
    array(N);
    for (const double value : values) {
      f64(value);
    }
  }

  std::vector<std::uint8_t> take() {return std::move(out_);}

private:
  // msgpack_packer's write callback: appends to the Writer's output (`data` is out_).
  static int append(void * data, const char * bytes, std::size_t size);

  std::vector<std::uint8_t> out_;
  msgpack_packer packer_{};
};

// One text element of an array field (the generated write of a std::vector calls it).
inline void write(Writer & w, const std::string & text, const FieldPath & where)
{
  w.str(text, where);
}

// `params` maps: name -> bool, int, float, str or an array of one of those.
void write_params(Writer & w, const Params & params, const FieldPath & where);
// map<str,str> (a reply's `rejected`, `undeclared`).
void write_str_map(Writer & w, const StringMap & map, const FieldPath & where);

// EncodeError naming `where` unless `bytes` is the product of `sizes` (a costmap's cells).
void require_cells(
  std::size_t bytes, std::initializer_list<std::uint64_t> sizes, const FieldPath & where);

}  // namespace nav2_pyif_bridge::protocol::detail
