#include "json_tree.hpp"

#include <msgpack.h>
#include <zlib.h>

#include <cmath>
#include <cstddef>
#include <cstring>
#include <limits>
#include <optional>
#include <stdexcept>
#include <type_traits>
#include <utility>
#include <variant>

#include "nav2_pyif_bridge/protocol/fields.hpp"

namespace nav2_pyif_bridge::protocol::test
{
namespace
{

constexpr std::size_t kInlineBinLimit = 4096;

Json bin_json(const std::uint8_t * data, std::size_t size)
{
  if (size > kInlineBinLimit) {
    const auto crc = crc32(0L, data, static_cast<uInt>(size));
    return Json{{"$bin_len", size}, {"$bin_crc32", static_cast<std::uint64_t>(crc)}};
  }
  static const char * digits = "0123456789abcdef";
  std::string hex;
  hex.reserve(2 * size);
  for (std::size_t i = 0; i < size; ++i) {
    hex.push_back(digits[data[i] >> 4]);
    hex.push_back(digits[data[i] & 0xF]);
  }
  return Json{{"$bin", hex}};
}

Json bin_json(const std::vector<std::uint8_t> & bytes)
{
  return bin_json(bytes.data(), bytes.size());
}

// float64 values as little-endian bytes, written out byte by byte on purpose (an oracle
// independent of the codec's own packing).
Json packed_json(const std::vector<double> & values)
{
  std::vector<std::uint8_t> bytes;
  bytes.reserve(values.size() * 8);
  for (const double value : values) {
    std::uint64_t bits = 0;
    std::memcpy(&bits, &value, 8);
    for (int i = 0; i < 8; ++i) {
      bytes.push_back(static_cast<std::uint8_t>((bits >> (8 * i)) & 0xFF));
    }
  }
  return bin_json(bytes);
}

Json float_json(double value)
{
  if (std::isnan(value)) {
    return Json{{"$float", "nan"}};
  }
  if (std::isinf(value)) {
    return Json{{"$float", value > 0 ? "inf" : "-inf"}};
  }
  return Json(value);
}

template<std::size_t N>
Json floats_json(const std::array<double, N> & values)
{
  Json out = Json::array();
  for (const double value : values) {
    out.push_back(float_json(value));
  }
  return out;
}

template<class T>
struct IsOptional : std::false_type {};
template<class T>
struct IsOptional<std::optional<T>>: std::true_type {};

// An array field of the schema (`many`): a vector of structures or strings.
template<class T>
struct IsArrayField : std::false_type {};
template<class T>
struct IsArrayField<std::vector<T>>: std::bool_constant<!std::is_arithmetic_v<T>> {};

template<class T>
struct IsFloatArray : std::false_type {};
template<std::size_t N>
struct IsFloatArray<std::array<double, N>>: std::true_type {};

Json param_json(const ParamValue & value);

// Any field of any message, by its C++ type; structures and bodies field by field, through the
// generated for_each_field (in wire order, absent optional fields left out).
template<class T>
Json value_json(const T & value)
{
  if constexpr (std::is_same_v<T, double>) {
    return float_json(value);
  } else if constexpr (std::is_same_v<T, std::string> || std::is_integral_v<T>) {
    return Json(value);
  } else if constexpr (std::is_same_v<T, std::vector<std::uint8_t>>) {
    return bin_json(value);
  } else if constexpr (std::is_same_v<T, std::vector<double>>) {
    return packed_json(value);  // the only top-level float vectors are packed rows
  } else if constexpr (IsFloatArray<T>::value) {
    return floats_json(value);
  } else if constexpr (IsArrayField<T>::value) {
    Json out = Json::array();
    for (const auto & item : value) {
      out.push_back(value_json(item));
    }
    return out;
  } else if constexpr (std::is_same_v<T, Params>|| std::is_same_v<T, StringMap>) {
    Json out = Json::object();
    for (const auto & [name, item] : value) {
      if constexpr (std::is_same_v<T, Params>) {
        out[name] = param_json(item);
      } else {
        out[name] = item;
      }
    }
    return out;
  } else {
    Json out = Json::object();  // `{}` for an empty body, whatever its op
    for_each_field(
      value, [&out](const char * name, const auto & field) {
        using Field = std::decay_t<decltype(field)>;
        if constexpr (IsOptional<Field>::value) {
          if (field) {
            out[name] = value_json(*field);
          }
        } else {
          out[name] = value_json(field);
        }
      });
    return out;
  }
}

Json param_json(const ParamValue & value)
{
  return std::visit(
    [](const auto & v) -> Json {
      using T = std::decay_t<decltype(v)>;
      if constexpr (std::is_same_v<T, double>) {
        return float_json(v);
      } else if constexpr (std::is_same_v<T, std::vector<double>>) {
        Json out = Json::array();
        for (const double item : v) {
          out.push_back(float_json(item));
        }
        return out;
      } else if constexpr (std::is_same_v<T, std::vector<bool>>) {
        Json out = Json::array();
        for (const bool item : v) {
          out.push_back(item);
        }
        return out;
      } else {
        return Json(v);
      }
    },
    value);
}

// --- comparison ---------------------------------------------------------------------------

// An integer as (negative, magnitude): JSON parsers keep non-negative ints unsigned and the
// typed structs give signed ones, and only the value matters.
std::pair<bool, std::uint64_t> int_value(const Json & j)
{
  if (j.is_number_unsigned()) {
    return {false, j.get<std::uint64_t>()};
  }
  const auto v = j.get<std::int64_t>();
  return v < 0 ? std::make_pair(true, static_cast<std::uint64_t>(-(v + 1)) + 1) :
         std::make_pair(false, static_cast<std::uint64_t>(v));
}

std::string kind(const Json & j)
{
  if (j.is_number_integer()) {
    return "int";
  }
  if (j.is_number_float()) {
    return "float";
  }
  return j.type_name();
}

std::string diff(const Json & expected, const Json & actual, const std::string & where)
{
  const std::string at = where.empty() ? "<root>" : where;
  if (kind(expected) != kind(actual)) {
    return at + ": expected " + kind(expected) + " " + expected.dump() + ", got " +
           kind(actual) + " " + actual.dump();
  }
  if (expected.is_object()) {
    auto e = expected.items().begin();
    auto a = actual.items().begin();
    for (; e != expected.items().end() && a != actual.items().end(); ++e, ++a) {
      if (e.key() != a.key()) {
        return at + ": expected key '" + e.key() + "', got key '" + a.key() + "' (order)";
      }
      std::string d = diff(e.value(), a.value(), where + "." + e.key());
      if (!d.empty()) {
        return d;
      }
    }
    if (expected.size() != actual.size()) {
      return at + ": expected " + std::to_string(expected.size()) + " keys " + expected.dump() +
             ", got " + std::to_string(actual.size()) + " " + actual.dump();
    }
    return "";
  }
  if (expected.is_array()) {
    if (expected.size() != actual.size()) {
      return at + ": expected " + std::to_string(expected.size()) + " elements, got " +
             std::to_string(actual.size());
    }
    for (std::size_t i = 0; i < expected.size(); ++i) {
      std::string d = diff(expected[i], actual[i], where + "[" + std::to_string(i) + "]");
      if (!d.empty()) {
        return d;
      }
    }
    return "";
  }
  bool equal = false;
  if (expected.is_number_integer()) {
    equal = int_value(expected) == int_value(actual);
  } else if (expected.is_number_float()) {
    const double e = expected.get<double>();
    const double a = actual.get<double>();
    equal = std::memcmp(&e, &a, sizeof e) == 0;
  } else {
    equal = expected == actual;
  }
  return equal ? "" : at + ": expected " + expected.dump() + ", got " + actual.dump();
}

// --- packing ------------------------------------------------------------------------------

std::string unhex(const std::string & hex)
{
  std::string out;
  for (std::size_t i = 0; i + 1 < hex.size(); i += 2) {
    out.push_back(static_cast<char>(std::stoi(hex.substr(i, 2), nullptr, 16)));
  }
  return out;
}

// msgpack-c's packer, writing into `out`.
struct Sink
{
  explicit Sink(std::vector<std::uint8_t> & bytes)
  : out(bytes)
  {
    msgpack_packer_init(&packer, &out, &Sink::append);
  }

  static int append(void * data, const char * bytes, std::size_t size)
  {
    auto & out = *static_cast<std::vector<std::uint8_t> *>(data);
    out.insert(out.end(), bytes, bytes + size);
    return 0;
  }

  std::vector<std::uint8_t> & out;
  msgpack_packer packer{};
};

// float64 / float32 written by hand: these trees need the exact float forms, whatever a
// msgpack-c release's pack_double and pack_float do with whole numbers.
template<class Float, class Bits>
void pack_float_bits(Sink & sink, std::uint8_t marker, Float value)
{
  Bits bits = 0;
  std::memcpy(&bits, &value, sizeof bits);
  std::uint8_t buf[1 + sizeof bits];
  buf[0] = marker;
  for (std::size_t i = 0; i < sizeof bits; ++i) {
    buf[1 + i] = static_cast<std::uint8_t>((bits >> (8 * (sizeof bits - 1 - i))) & 0xFF);
  }
  sink.out.insert(sink.out.end(), buf, buf + sizeof buf);
}

void pack(Sink & sink, const Json & j)
{
  switch (j.type()) {
    case Json::value_t::null:
      msgpack_pack_nil(&sink.packer);
      return;
    case Json::value_t::boolean:
      if (j.get<bool>()) {
        msgpack_pack_true(&sink.packer);
      } else {
        msgpack_pack_false(&sink.packer);
      }
      return;
    case Json::value_t::number_unsigned:
      msgpack_pack_uint64(&sink.packer, j.get<std::uint64_t>());
      return;
    case Json::value_t::number_integer:
      msgpack_pack_int64(&sink.packer, j.get<std::int64_t>());
      return;
    case Json::value_t::number_float:
      pack_float_bits<double, std::uint64_t>(sink, 0xcb, j.get<double>());
      return;
    case Json::value_t::string: {
        const auto & s = j.get_ref<const std::string &>();
        msgpack_pack_str(&sink.packer, s.size());
        msgpack_pack_str_body(&sink.packer, s.data(), s.size());
        return;
      }
    case Json::value_t::array:
      msgpack_pack_array(&sink.packer, j.size());
      for (const auto & item : j) {
        pack(sink, item);
      }
      return;
    case Json::value_t::object:
      if (j.size() == 1 && j.contains("$bin")) {
        const std::string bytes = unhex(j["$bin"].get<std::string>());
        msgpack_pack_bin(&sink.packer, bytes.size());
        msgpack_pack_bin_body(&sink.packer, bytes.data(), bytes.size());
        return;
      }
      if (j.size() == 1 && j.contains("$float")) {
        const auto name = j["$float"].get<std::string>();
        const double inf = std::numeric_limits<double>::infinity();
        pack_float_bits<double, std::uint64_t>(
          sink, 0xcb, name == "nan" ? std::numeric_limits<double>::quiet_NaN() :
          name == "inf" ? inf : -inf);
        return;
      }
      if (j.size() == 1 && j.contains("$float32")) {
        pack_float_bits<float, std::uint32_t>(sink, 0xca, j["$float32"].get<float>());
        return;
      }
      if (j.contains("$bin_len")) {
        throw std::invalid_argument("pack_json: a bin above 4 KiB has no bytes in its JSON form");
      }
      msgpack_pack_map(&sink.packer, j.size());
      for (const auto & item : j.items()) {
        msgpack_pack_str(&sink.packer, item.key().size());
        msgpack_pack_str_body(&sink.packer, item.key().data(), item.key().size());
        pack(sink, item.value());
      }
      return;
    default:
      throw std::invalid_argument("pack_json: cannot pack " + std::string(j.type_name()));
  }
}

}  // namespace

Json to_json(const Request & request)
{
  Json out = Json::object();
  out["v"] = request.v;
  out["op"] = std::string(op_name(request.op()));
  out["sid"] = request.sid;
  out["epoch"] = request.epoch;
  out["seq"] = request.seq;
  out["body"] = std::visit([](const auto & body) {return value_json(body);}, request.body);
  return out;
}

Json to_json(const Reply & reply)
{
  Json out = Json::object();
  out["v"] = reply.v;
  out["seq"] = reply.seq;
  out["ok"] = reply.ok();
  if (reply.ok()) {
    out["body"] = std::visit([](const auto & body) {return value_json(body);}, reply.body());
  } else {
    out["error"] = value_json(reply.error());
  }
  out["host"] = reply.host;
  out["compute_ns"] = reply.compute_ns;
  return out;
}

std::string first_difference(const Json & expected, const Json & actual)
{
  return diff(expected, actual, "");
}

std::vector<std::uint8_t> pack_json(const Json & tree)
{
  std::vector<std::uint8_t> out;
  Sink sink(out);
  pack(sink, tree);
  return out;
}

}  // namespace nav2_pyif_bridge::protocol::test
