// Force-included (-include) before anything else in every translation unit that includes ROS 1
// headers. ROS 1's generated message headers name `std::allocator<void>::rebind<T>::other`,
// which C++20 removed, while bipednav's own headers need C++20. This parses libstdc++'s
// <bits/allocator.h> alone in C++17 mode (its dependencies first in C++20 mode), so the
// std::allocator<void>::rebind member exists; every other header stays C++20. std::allocator is
// an empty class with inline members only, so the layout is the same either way.
#pragma once
#pragma GCC system_header
#if defined(__GLIBCXX__) || defined(__GNUC__)
#include <bits/c++config.h>
#include <bits/functexcept.h>
#include <bits/memoryfwd.h>
#include <bits/move.h>
#include <bits/new_allocator.h>

#include <new>
#include <type_traits>
#if __cplusplus > 201703L
#pragma push_macro("__cplusplus")
#undef __cplusplus
#define __cplusplus 201703L
#include <bits/allocator.h>
#pragma pop_macro("__cplusplus")
#endif
#endif
