// Parameter maps: `params` (configure, set_parameters) and `declared` (configure reply), and
// the `rejected` map of set_parameters replies.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <utility>
#include <variant>
#include <vector>

namespace nav2_pyif_bridge::protocol
{

// A parameter value: the scalar types of a ROS parameter and arrays of one of them. An empty
// msgpack array carries no element type; it decodes as an empty std::vector<double>.
// Construct values with explicit types (std::string{"fast"}, std::int64_t{30}): a string
// literal would otherwise convert to bool.
using ParamValue = std::variant<
  bool, std::int64_t, double, std::string,
  std::vector<bool>, std::vector<std::int64_t>, std::vector<double>, std::vector<std::string>>;

// A string-keyed map that keeps its entries in insertion order. The order is part of the
// canonical bytes (a peer's map re-encodes byte for byte only in its own order), which a
// std::map would lose by sorting. Parameter maps are small, so lookups are linear.
template<class Value>
class OrderedMap
{
public:
  using value_type = std::pair<std::string, Value>;
  using const_iterator = typename std::vector<value_type>::const_iterator;

  // Replaces the value of an existing name in place (keeping its position, as a Python dict
  // does), or appends a new entry.
  void set(std::string name, Value value)
  {
    if (Value * existing = find(name)) {
      *existing = std::move(value);
    } else {
      entries_.emplace_back(std::move(name), std::move(value));
    }
  }

  const Value * find(std::string_view name) const noexcept
  {
    for (const auto & entry : entries_) {
      if (entry.first == name) {
        return &entry.second;
      }
    }
    return nullptr;
  }

  Value * find(std::string_view name) noexcept
  {
    return const_cast<Value *>(static_cast<const OrderedMap &>(*this).find(name));
  }

  std::size_t size() const noexcept {return entries_.size();}
  bool empty() const noexcept {return entries_.empty();}
  const_iterator begin() const noexcept {return entries_.begin();}
  const_iterator end() const noexcept {return entries_.end();}

private:
  std::vector<value_type> entries_;
};

using Params = OrderedMap<ParamValue>;
using StringMap = OrderedMap<std::string>;

}  // namespace nav2_pyif_bridge::protocol
