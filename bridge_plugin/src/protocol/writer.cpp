#include "writer.hpp"

#include <cstring>
#include <limits>
#include <string>
#include <type_traits>
#include <variant>

#include "nav2_pyif_bridge/protocol/errors.hpp"
#include "cells.hpp"
#include "packed.hpp"
#include "utf8.hpp"

namespace nav2_pyif_bridge::protocol::detail
{
namespace
{

// msgpack lengths are 32-bit; nothing in this protocol comes near that, but a silent
// truncation would corrupt the message, so refuse it.
std::uint32_t length32(std::size_t size, const char * what)
{
  if (size > std::numeric_limits<std::uint32_t>::max()) {
    throw EncodeError(std::string(what) + " of " + std::to_string(size) +
            " elements exceeds msgpack's 32-bit length");
  }
  return static_cast<std::uint32_t>(size);
}

}  // namespace

Writer::Writer(std::size_t capacity_hint)
{
  out_.reserve(capacity_hint);
  msgpack_packer_init(&packer_, &out_, &Writer::append);
}

int Writer::append(void * data, const char * bytes, std::size_t size)
{
  auto & out = *static_cast<std::vector<std::uint8_t> *>(data);
  out.insert(out.end(), bytes, bytes + size);
  return 0;
}

void Writer::map(std::size_t entries)
{
  msgpack_pack_map(&packer_, length32(entries, "map"));
}

void Writer::array(std::size_t elements)
{
  msgpack_pack_array(&packer_, length32(elements, "array"));
}

void Writer::key(std::string_view name)
{
  const auto size = length32(name.size(), "str");
  msgpack_pack_str(&packer_, size);
  msgpack_pack_str_body(&packer_, name.data(), size);
}

void Writer::str(std::string_view text, const FieldPath & where)
{
  if (!is_valid_utf8(text.data(), text.size())) {
    throw EncodeError(where.str() + ": not valid UTF-8 (msgpack str is UTF-8 text)");
  }
  key(text);
}

void Writer::i64(std::int64_t value)
{
  // msgpack_pack_int64 picks the shortest form and writes non-negative values as unsigned,
  // exactly as msgpack-python does; the vectors check both.
  msgpack_pack_int64(&packer_, value);
}

void Writer::u64(std::uint64_t value)
{
  msgpack_pack_uint64(&packer_, value);
}

void Writer::f64(double value)
{
  // Written by hand, so the canonical form (always float64, never an int for a whole number)
  // holds whatever a msgpack-c release does: float64 is 0xcb + 8 bytes big-endian.
  std::uint64_t bits = 0;
  std::memcpy(&bits, &value, sizeof bits);
  std::uint8_t buf[9];
  buf[0] = 0xcb;
  for (int i = 0; i < 8; ++i) {
    buf[1 + i] = static_cast<std::uint8_t>((bits >> (56 - 8 * i)) & 0xFF);
  }
  out_.insert(out_.end(), buf, buf + sizeof buf);
}

void Writer::boolean(bool value)
{
  if (value) {
    msgpack_pack_true(&packer_);
  } else {
    msgpack_pack_false(&packer_);
  }
}

void Writer::bin(const std::uint8_t * data, std::size_t size)
{
  const auto size32 = length32(size, "bin");
  msgpack_pack_bin(&packer_, size32);
  msgpack_pack_bin_body(&packer_, data, size32);
}

void Writer::rows(const std::vector<double> & values, std::size_t row_size, const FieldPath & where)
{
  if (values.size() % row_size != 0) {
    throw EncodeError(where.str() + ": " + std::to_string(values.size()) +
            " values is not a whole number of rows of " + std::to_string(row_size));
  }
  const std::size_t bytes = values.size() * 8;
  msgpack_pack_bin(&packer_, length32(bytes, "bin"));
  // The body goes straight into the output (no temporary buffer for a 1000-pose plan).
  const std::size_t start = out_.size();
  out_.resize(start + bytes);
  std::uint8_t * cursor = out_.data() + start;
  for (const double value : values) {
    store_f64_le(value, cursor);
    cursor += 8;
  }
}

namespace
{

template<class... Fs>
struct Overloaded : Fs ...
{
  using Fs::operator()...;
};
template<class... Fs>
Overloaded(Fs...)->Overloaded<Fs...>;

template<class T, class WriteOne>
void write_array(Writer & w, const std::vector<T> & items, WriteOne write_one)
{
  w.array(items.size());
  for (std::size_t i = 0; i < items.size(); ++i) {
    write_one(items[i], i);
  }
}

void write_param(Writer & w, const ParamValue & value, const FieldPath & where)
{
  std::visit(
    Overloaded{
      [&](bool v) {w.boolean(v);},
      [&](std::int64_t v) {w.i64(v);},
      [&](double v) {w.f64(v);},
      [&](const std::string & v) {w.str(v, where);},
      [&](const std::vector<bool> & v) {
        write_array(w, v, [&](bool item, std::size_t) {w.boolean(item);});
      },
      [&](const std::vector<std::int64_t> & v) {
        write_array(w, v, [&](std::int64_t item, std::size_t) {w.i64(item);});
      },
      [&](const std::vector<double> & v) {
        write_array(w, v, [&](double item, std::size_t) {w.f64(item);});
      },
      [&](const std::vector<std::string> & v) {
        write_array(
          w, v, [&](const std::string & item, std::size_t i) {w.str(item, where.index(i));});
      },
    },
    value);
}

}  // namespace

void write_params(Writer & w, const Params & params, const FieldPath & where)
{
  w.map(params.size());
  for (const auto & [name, value] : params) {
    w.str(name, where);
    write_param(w, value, where.param(name));
  }
}

void write_str_map(Writer & w, const StringMap & map, const FieldPath & where)
{
  w.map(map.size());
  for (const auto & [name, value] : map) {
    w.str(name, where);
    w.str(value, where.param(name));
  }
}

void require_cells(
  std::size_t bytes, std::initializer_list<std::uint64_t> sizes, const FieldPath & where)
{
  const std::string problem = cells_problem(bytes, sizes);
  if (!problem.empty()) {
    throw EncodeError(where.str() + ": " + problem);
  }
}

}  // namespace nav2_pyif_bridge::protocol::detail
