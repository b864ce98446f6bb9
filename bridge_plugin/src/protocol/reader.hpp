// Typed reads of a decoded msgpack tree, each naming the field at fault when the tree breaks
// the schema. The generated body_codec.cpp and envelopes.cpp say *which* fields a message has;
// this says how each kind of field is read and checked (PROTOCOL.md section 2: an int is
// accepted where a float is specified, nil counts as absent, unknown keys are ignored), and
// how the envelope fields with a rule of their own are read (the version, the op, the body).
#pragma once

#include <msgpack.h>

#include <array>
#include <cstddef>
#include <cstdint>
#include <initializer_list>
#include <optional>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <vector>

#include "field_path.hpp"
#include "nav2_pyif_bridge/protocol/ops.hpp"
#include "nav2_pyif_bridge/protocol/params.hpp"

namespace nav2_pyif_bridge::protocol::detail
{

// msgpack-c's object tree (msgpack.h): the C library the rosdep key `msgpack` installs.
using Object = msgpack_object;

// Throws DecodeError (BadRequest) for the field at `where`.
[[noreturn]] void fail(const FieldPath & where, const std::string & problem);

// The msgpack name of an object's type ("int", "str", "array", ...), for "got ..." messages.
const char * type_name(const Object & object) noexcept;

std::string read_str(const Object & object, const FieldPath & where);
bool read_bool(const Object & object, const FieldPath & where);
std::int64_t read_i64(const Object & object, const FieldPath & where);
std::uint64_t read_u64(const Object & object, const FieldPath & where);
std::uint32_t read_u32(const Object & object, const FieldPath & where);
double read_f64(const Object & object, const FieldPath & where);
std::vector<std::uint8_t> read_bin(const Object & object, const FieldPath & where);
// A packed little-endian float64 array whose length is a whole number of rows.
std::vector<double> read_packed_f64(
  const Object & object, const FieldPath & where, std::size_t row_size);
template<std::size_t RowSize>
std::vector<double> read_rows(const Object & object, const FieldPath & where)
{
  return read_packed_f64(object, where, RowSize);
}
Params read_params(const Object & object, const FieldPath & where);
StringMap read_str_map(const Object & object, const FieldPath & where);

// DecodeError naming `where` unless `bytes` is the product of `sizes` (a costmap's cells).
void expect_cells(
  std::size_t bytes, std::initializer_list<std::uint64_t> sizes, const FieldPath & where);

// A msgpack array of exactly N floats (float[6], float[7]).
void read_f64_array(const Object & object, const FieldPath & where, double * out, std::size_t n);
template<std::size_t N>
std::array<double, N> read_f64_array(const Object & object, const FieldPath & where)
{
  std::array<double, N> out{};
  read_f64_array(object, where, out.data(), N);
  return out;
}

// The elements of a msgpack array (throws unless `object` is one).
const msgpack_object_array & read_array_items(const Object & object, const FieldPath & where);
// An array field (`many` in the schema): each element read by Read, naming its index in errors.
template<auto Read>
auto read_array(const Object & object, const FieldPath & where)
{
  const msgpack_object_array & items = read_array_items(object, where);
  std::vector<decltype(Read(object, where))> out;
  out.reserve(items.size);
  for (std::uint32_t i = 0; i < items.size; ++i) {
    out.push_back(Read(items.ptr[i], where.index(i)));
  }
  return out;
}

// An int field with a `minimum` in the schema (a request's epoch): read by Read, and refused
// when smaller.
template<auto Read, auto Minimum>
auto read_at_least(const Object & object, const FieldPath & where)
{
  const auto value = Read(object, where);
  if (value < static_cast<std::remove_const_t<decltype(value)>>(Minimum)) {
    fail(where, "expected an int >= " + std::to_string(Minimum) + ", got " +
      std::to_string(value));
  }
  return value;
}

// An op's name (the envelope's Role.OP field): DecodeError listing the known ones when it is
// none of them.
Op read_op(const Object & object, const FieldPath & where);

// A map with string keys, read field by field.
class MapReader
{
public:
  // Throws unless `object` is a map.
  MapReader(const Object & object, const FieldPath & where);

  // nullptr when the key is absent or nil. A repeated key counts with its last value, as in
  // a Python dict.
  const Object * find(std::string_view key) const noexcept;

  // `read(object, path)` on a field that must be present.
  template<class Read>
  auto required(std::string_view key, Read read) const
  {
    const Object * object = find(key);
    if (object == nullptr) {
      fail(where_, "missing field '" + std::string(key) + "'");
    }
    return read(*object, where_.key(key));
  }

  // `read(object, path)` on a field that may be absent.
  template<class Read>
  auto optional(std::string_view key, Read read) const
  ->std::optional<decltype(read(std::declval<const Object &>(), std::declval<FieldPath>()))>
  {
    const Object * object = find(key);
    if (object == nullptr) {
      return std::nullopt;
    }
    return read(*object, where_.key(key));
  }

  const FieldPath & where() const noexcept {return where_;}

private:
  const msgpack_object_map & map_;
  // A copy, so a MapReader built from a temporary path stays valid; the parents it points
  // to live further up the stack.
  FieldPath where_;
};

// The envelope's version (Role.VERSION), read before any other field: a message of another
// version may differ in anything else. A DecodeError of type VersionMismatch, naming what the
// message is ("request"), unless it is kProtocolVersion.
std::int64_t read_version(const MapReader & message, std::string_view key);

// The envelope's body map (a BODY field), or an empty one when absent: the Python codec reads a
// missing body as {}.
const Object & body_map(const MapReader & message, std::string_view key);

}  // namespace nav2_pyif_bridge::protocol::detail
