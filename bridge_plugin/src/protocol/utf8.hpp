// UTF-8 validation. msgpack `str` is UTF-8 text, and the Python codec refuses anything else,
// so this codec checks strings both ways: a bad frame id fails here, naming the field, not as
// an unreadable message on the host.
#pragma once

#include <cstddef>

namespace nav2_pyif_bridge::protocol::detail
{

// Well-formed UTF-8 as Python decodes it: no overlong forms, no surrogates, <= U+10FFFF.
bool is_valid_utf8(const char * data, std::size_t size) noexcept;

}  // namespace nav2_pyif_bridge::protocol::detail
