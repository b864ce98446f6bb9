# Which Nav2 plugin API the package is built against, from the files nav2_core installs (one
# tree for every distribution; nav2_pyif_bridge/nav2_api.hpp reads the same files when these
# are not defined):
#   NAV2_PYIF_JAZZY_API    nav2_core/controller_exceptions.hpp: Jazzy, Kilted, Lyrical (the
#                          controller and planner exceptions, cancel/reset, the cancel checker)
#   NAV2_PYIF_LYRICAL_API  nav2_core/path_handler.hpp: Lyrical, navigation2 1.5+ (the
#                          transformed plan, viapoints, isGoalXYReached, nav2::LifecycleNode)
# nav2_core's include folders come from nav2_core_INCLUDE_DIRS (ament_export_include_directories,
# up to Kilted) or its exported target's interface (Lyrical's nav2_core exports only the target).

function(nav2_pyif_nav2_core_include_dirs out)
  set(dirs ${nav2_core_INCLUDE_DIRS})
  foreach(target nav2_core::nav2_core ${nav2_core_TARGETS})
    if(TARGET ${target})
      get_target_property(target_dirs ${target} INTERFACE_INCLUDE_DIRECTORIES)
      if(target_dirs)
        list(APPEND dirs ${target_dirs})
      endif()
    endif()
  endforeach()
  set(${out} ${dirs} PARENT_SCOPE)
endfunction()

function(nav2_pyif_has_nav2_core_header header out)
  nav2_pyif_nav2_core_include_dirs(dirs)
  set(found 0)
  foreach(dir IN LISTS dirs)
    if(EXISTS "${dir}/${header}")
      set(found 1)
    endif()
  endforeach()
  set(${out} ${found} PARENT_SCOPE)
endfunction()

nav2_pyif_has_nav2_core_header(nav2_core/controller_exceptions.hpp NAV2_PYIF_JAZZY_API)
nav2_pyif_has_nav2_core_header(nav2_core/path_handler.hpp NAV2_PYIF_LYRICAL_API)
if(NAV2_PYIF_LYRICAL_API)
  message(STATUS "nav2_pyif_bridge: Nav2 Lyrical API (path handler, viapoints, nav2::LifecycleNode)")
elseif(NAV2_PYIF_JAZZY_API)
  message(STATUS "nav2_pyif_bridge: Nav2 Jazzy/Kilted API (controller and planner exceptions)")
else()
  message(STATUS "nav2_pyif_bridge: Nav2 Humble API (PlannerException only)")
endif()
