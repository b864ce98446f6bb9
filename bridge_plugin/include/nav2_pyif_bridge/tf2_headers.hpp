// tf2's headers the plugin uses. geometry2 0.45 (Lyrical) renamed tf2's `.h` headers to
// `.hpp` (the `.h` ones only warn that they are obsolete); Humble and Jazzy have only `.h`.
#pragma once

#if __has_include(<tf2/utils.hpp>)
#  include "tf2/LinearMath/Quaternion.hpp"
#  include "tf2/exceptions.hpp"
#  include "tf2/time.hpp"
#  include "tf2/utils.hpp"
#else
#  include "tf2/LinearMath/Quaternion.h"
#  include "tf2/exceptions.h"
#  include "tf2/time.h"
#  include "tf2/utils.h"
#endif
#include "tf2_geometry_msgs/tf2_geometry_msgs.hpp"
