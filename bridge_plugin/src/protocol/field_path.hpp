// Where in a message the codec is, for error messages such as
// "compute_velocity_commands request body.pose.frame_id: expected str, got int".
//
// A path is a chain of stack-allocated nodes, each pointing at its parent, and is rendered to
// text only when an error is thrown: the happy path builds no strings.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

namespace nav2_pyif_bridge::protocol::detail
{

class FieldPath
{
public:
  // A root label in two parts (e.g. "set_plan" + " request body"), so no string is built.
  explicit FieldPath(std::string_view label, std::string_view label_suffix = {}) noexcept
  : label_(label), suffix_(label_suffix) {}

  // Children refer to their parent: use them within the parent's lifetime (as arguments).
  FieldPath key(std::string_view name) const noexcept {return {this, Kind::Key, name, 0};}
  FieldPath index(std::size_t i) const noexcept {return {this, Kind::Index, {}, i};}
  FieldPath param(std::string_view name) const noexcept {return {this, Kind::Param, name, 0};}

  // ".pose.frame_id" style, with "[3]" for array elements and "['name']" for parameters.
  std::string str() const
  {
    std::string out = parent_ ? parent_->str() : std::string{};
    switch (kind_) {
      case Kind::Root:
        out.append(label_).append(suffix_);
        break;
      case Kind::Key:
        out.append(".").append(label_);
        break;
      case Kind::Index:
        out.append("[").append(std::to_string(index_)).append("]");
        break;
      case Kind::Param:
        out.append("['").append(label_).append("']");
        break;
    }
    return out;
  }

private:
  enum class Kind { Root, Key, Index, Param };

  FieldPath(const FieldPath * parent, Kind kind, std::string_view label, std::size_t i) noexcept
  : parent_(parent), kind_(kind), label_(label), index_(i) {}

  const FieldPath * parent_{nullptr};
  Kind kind_{Kind::Root};
  std::string_view label_;
  std::string_view suffix_;
  std::size_t index_{0};
};

}  // namespace nav2_pyif_bridge::protocol::detail
