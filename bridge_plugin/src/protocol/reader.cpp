#include "reader.hpp"

#include <limits>
#include <set>
#include <type_traits>
#include <variant>

#include "nav2_pyif_bridge/protocol/constants.hpp"
#include "nav2_pyif_bridge/protocol/errors.hpp"
#include "cells.hpp"
#include "packed.hpp"
#include "utf8.hpp"

namespace nav2_pyif_bridge::protocol::detail
{
namespace
{

std::string expected(const char * what, const Object & object)
{
  return std::string("expected ") + what + ", got " + type_name(object);
}

bool is_int(const Object & object) noexcept
{
  return object.type == MSGPACK_OBJECT_POSITIVE_INTEGER ||
         object.type == MSGPACK_OBJECT_NEGATIVE_INTEGER;
}

// The value of an int object as text, for range errors.
std::string int_text(const Object & object)
{
  return object.type == MSGPACK_OBJECT_POSITIVE_INTEGER ? std::to_string(object.via.u64) :
         std::to_string(object.via.i64);
}

std::string_view str_view(const Object & object) noexcept
{
  return {object.via.str.ptr, object.via.str.size};
}

// One element of a parameter: bool, int, float or str, nothing else (no nil, bin, maps or
// nested arrays), like a ROS parameter.
using Scalar = std::variant<bool, std::int64_t, double, std::string>;

Scalar read_scalar(const Object & object, const FieldPath & where, std::string_view name)
{
  switch (object.type) {
    case MSGPACK_OBJECT_BOOLEAN:
      return object.via.boolean;
    case MSGPACK_OBJECT_POSITIVE_INTEGER:
    case MSGPACK_OBJECT_NEGATIVE_INTEGER:
      return read_i64(object, where);
    case MSGPACK_OBJECT_FLOAT32:
    case MSGPACK_OBJECT_FLOAT64:
      return object.via.f64;
    case MSGPACK_OBJECT_STR:
      return read_str(object, where);
    default:
      fail(where, "parameter '" + std::string(name) + "': " + type_name(object) +
        " is not bool/int/float/str or an array of one of those");
  }
}

// Scalars of one type -> the std::vector alternative of ParamValue for that type.
template<class T>
ParamValue collect(const std::vector<Scalar> & items)
{
  std::vector<T> out;
  out.reserve(items.size());
  for (const Scalar & item : items) {
    out.push_back(std::get<T>(item));
  }
  return out;
}

ParamValue read_param(const Object & object, const FieldPath & where, std::string_view name)
{
  if (object.type != MSGPACK_OBJECT_ARRAY) {
    return std::visit([](auto && value) -> ParamValue {return value;},
             read_scalar(object, where, name));
  }
  const auto & array = object.via.array;
  std::vector<Scalar> items;
  items.reserve(array.size);
  std::set<std::string> kinds;  // the element types met, for the "mixes" error
  for (std::uint32_t i = 0; i < array.size; ++i) {
    items.push_back(read_scalar(array.ptr[i], where.index(i), name));
    kinds.insert(type_name(array.ptr[i]));
  }
  if (kinds.size() > 1) {
    std::string names;
    for (const auto & kind : kinds) {
      names += (names.empty() ? "" : " and ") + kind;
    }
    fail(where, "parameter '" + std::string(name) + "': array mixes " + names);
  }
  if (items.empty()) {
    return std::vector<double>{};  // no element says which type; see params.hpp
  }
  switch (items.front().index()) {
    case 0:
      return collect<bool>(items);
    case 1:
      return collect<std::int64_t>(items);
    case 2:
      return collect<double>(items);
    default:
      return collect<std::string>(items);
  }
}

std::string known_ops()
{
  std::string out;
  for (const auto name : kOpNames) {
    out.append(out.empty() ? "" : ", ").append(name);
  }
  return out;
}

}  // namespace

void fail(const FieldPath & where, const std::string & problem)
{
  throw DecodeError(error_type::kBadRequest, where.str(), problem);
}

const char * type_name(const Object & object) noexcept
{
  switch (object.type) {
    case MSGPACK_OBJECT_NIL:
      return "nil";
    case MSGPACK_OBJECT_BOOLEAN:
      return "bool";
    case MSGPACK_OBJECT_POSITIVE_INTEGER:
    case MSGPACK_OBJECT_NEGATIVE_INTEGER:
      return "int";
    case MSGPACK_OBJECT_FLOAT32:
    case MSGPACK_OBJECT_FLOAT64:
      return "float";
    case MSGPACK_OBJECT_STR:
      return "str";
    case MSGPACK_OBJECT_BIN:
      return "bin";
    case MSGPACK_OBJECT_ARRAY:
      return "array";
    case MSGPACK_OBJECT_MAP:
      return "map";
    case MSGPACK_OBJECT_EXT:
      return "ext";
  }
  return "unknown";
}

std::string read_str(const Object & object, const FieldPath & where)
{
  if (object.type != MSGPACK_OBJECT_STR) {
    fail(where, expected("str", object));
  }
  if (!is_valid_utf8(object.via.str.ptr, object.via.str.size)) {
    fail(where, "str is not valid UTF-8");
  }
  return std::string(str_view(object));
}

bool read_bool(const Object & object, const FieldPath & where)
{
  if (object.type != MSGPACK_OBJECT_BOOLEAN) {
    fail(where, expected("bool", object));
  }
  return object.via.boolean;
}

std::int64_t read_i64(const Object & object, const FieldPath & where)
{
  if (object.type == MSGPACK_OBJECT_NEGATIVE_INTEGER) {
    return object.via.i64;
  }
  if (object.type != MSGPACK_OBJECT_POSITIVE_INTEGER) {
    fail(where, expected("int", object));
  }
  if (object.via.u64 > static_cast<std::uint64_t>(std::numeric_limits<std::int64_t>::max())) {
    fail(where, "int " + int_text(object) + " is out of the int64 range");
  }
  return static_cast<std::int64_t>(object.via.u64);
}

std::uint64_t read_u64(const Object & object, const FieldPath & where)
{
  if (!is_int(object)) {
    fail(where, expected("int", object));
  }
  if (object.type == MSGPACK_OBJECT_NEGATIVE_INTEGER) {
    fail(where, "expected an int >= 0, got " + int_text(object));
  }
  return object.via.u64;
}

std::uint32_t read_u32(const Object & object, const FieldPath & where)
{
  const std::uint64_t value = read_u64(object, where);
  if (value > std::numeric_limits<std::uint32_t>::max()) {
    fail(where, "int " + int_text(object) + " is out of the uint32 range");
  }
  return static_cast<std::uint32_t>(value);
}

double read_f64(const Object & object, const FieldPath & where)
{
  switch (object.type) {
    case MSGPACK_OBJECT_FLOAT32:  // msgpack-c widens float32 into via.f64
    case MSGPACK_OBJECT_FLOAT64:
      return object.via.f64;
    case MSGPACK_OBJECT_POSITIVE_INTEGER:  // a peer may send a whole number as an int
      return static_cast<double>(object.via.u64);
    case MSGPACK_OBJECT_NEGATIVE_INTEGER:
      return static_cast<double>(object.via.i64);
    default:
      fail(where, expected("float", object));
  }
}

std::vector<std::uint8_t> read_bin(const Object & object, const FieldPath & where)
{
  if (object.type != MSGPACK_OBJECT_BIN) {
    fail(where, expected("bin", object));
  }
  const auto * data = reinterpret_cast<const std::uint8_t *>(object.via.bin.ptr);
  return std::vector<std::uint8_t>(data, data + object.via.bin.size);
}

std::vector<double> read_packed_f64(
  const Object & object, const FieldPath & where, std::size_t row_size)
{
  if (object.type != MSGPACK_OBJECT_BIN) {
    fail(where, expected("bin", object));
  }
  const std::size_t size = object.via.bin.size;
  if (size % (row_size * 8) != 0) {
    fail(where, std::to_string(size) + " bytes is not a whole number of rows of " +
      std::to_string(row_size) + " float64 (" + std::to_string(row_size * 8) + " bytes)");
  }
  const auto * data = reinterpret_cast<const std::uint8_t *>(object.via.bin.ptr);
  std::vector<double> out(size / 8);
  for (std::size_t i = 0; i < out.size(); ++i) {
    out[i] = load_f64_le(data + 8 * i);
  }
  return out;
}

void expect_cells(
  std::size_t bytes, std::initializer_list<std::uint64_t> sizes, const FieldPath & where)
{
  const std::string problem = cells_problem(bytes, sizes);
  if (!problem.empty()) {
    fail(where, problem);
  }
}

void read_f64_array(const Object & object, const FieldPath & where, double * out, std::size_t n)
{
  if (object.type != MSGPACK_OBJECT_ARRAY) {
    fail(where, "expected an array of " + std::to_string(n) + " floats, got " +
      type_name(object));
  }
  if (object.via.array.size != n) {
    fail(where, "expected an array of " + std::to_string(n) + " floats, got " +
      std::to_string(object.via.array.size));
  }
  for (std::size_t i = 0; i < n; ++i) {
    out[i] = read_f64(object.via.array.ptr[i], where.index(i));
  }
}

const msgpack_object_array & read_array_items(const Object & object, const FieldPath & where)
{
  if (object.type != MSGPACK_OBJECT_ARRAY) {
    fail(where, expected("an array", object));
  }
  return object.via.array;
}

Op read_op(const Object & object, const FieldPath & where)
{
  const std::string name = read_str(object, where);
  const auto op = op_from_name(name);
  if (!op) {
    fail(where, "unknown op '" + name + "'; known: " + known_ops());
  }
  return *op;
}

Params read_params(const Object & object, const FieldPath & where)
{
  if (object.type != MSGPACK_OBJECT_MAP) {
    fail(where, expected("a map of parameters", object));
  }
  Params out;
  const auto & map = object.via.map;
  for (std::uint32_t i = 0; i < map.size; ++i) {
    const Object & key = map.ptr[i].key;
    if (key.type != MSGPACK_OBJECT_STR) {
      fail(where, std::string("a parameter name is ") + type_name(key) + ", not str");
    }
    const std::string name = read_str(key, where);
    out.set(name, read_param(map.ptr[i].val, where.param(name), name));
  }
  return out;
}

StringMap read_str_map(const Object & object, const FieldPath & where)
{
  if (object.type != MSGPACK_OBJECT_MAP) {
    fail(where, expected("a map of str to str", object));
  }
  StringMap out;
  const auto & map = object.via.map;
  for (std::uint32_t i = 0; i < map.size; ++i) {
    std::string name = read_str(map.ptr[i].key, where);
    std::string value = read_str(map.ptr[i].val, where.param(name));
    out.set(std::move(name), std::move(value));
  }
  return out;
}

MapReader::MapReader(const Object & object, const FieldPath & where)
: map_(object.via.map), where_(where)
{
  if (object.type != MSGPACK_OBJECT_MAP) {
    fail(where, expected("map", object));
  }
}

const Object * MapReader::find(std::string_view key) const noexcept
{
  const Object * found = nullptr;
  for (std::uint32_t i = 0; i < map_.size; ++i) {
    const Object & k = map_.ptr[i].key;
    if (k.type == MSGPACK_OBJECT_STR && str_view(k) == key) {
      found = &map_.ptr[i].val;  // keep scanning: the last duplicate wins
    }
  }
  if (found != nullptr && found->type == MSGPACK_OBJECT_NIL) {
    return nullptr;
  }
  return found;
}

std::int64_t read_version(const MapReader & message, std::string_view key)
{
  const Object * v = message.find(key);
  if (v != nullptr && v->type == MSGPACK_OBJECT_POSITIVE_INTEGER &&
    v->via.u64 == static_cast<std::uint64_t>(kProtocolVersion))
  {
    return kProtocolVersion;
  }
  std::string theirs = "missing";
  if (v != nullptr) {
    theirs = v->type == MSGPACK_OBJECT_POSITIVE_INTEGER ? std::to_string(v->via.u64) :
      v->type == MSGPACK_OBJECT_NEGATIVE_INTEGER ? std::to_string(v->via.i64) :
      std::string("of type ") + type_name(*v);
  }
  const std::string what = message.where().str();
  throw DecodeError(
          error_type::kVersionMismatch, message.where().key(key).str(),
          what + " speaks protocol version " + theirs + "; this codec speaks " +
          std::to_string(kProtocolVersion));
}

const Object & body_map(const MapReader & message, std::string_view key)
{
  static const Object empty_map = [] {
      Object o{};
      o.type = MSGPACK_OBJECT_MAP;
      o.via.map.size = 0;
      o.via.map.ptr = nullptr;
      return o;
    }();
  const Object * body = message.find(key);
  return body != nullptr ? *body : empty_map;
}

}  // namespace nav2_pyif_bridge::protocol::detail
