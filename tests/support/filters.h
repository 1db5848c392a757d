// Every mip filter kind and wrap mode, for tests that sweep them all.
#pragma once

#include "texproc/filters.h"

namespace texproc::test {

inline constexpr FilterKind kAllFilters[] = {FilterKind::box,    FilterKind::triangle, FilterKind::gaussian,
                                             FilterKind::kaiser, FilterKind::lanczos3, FilterKind::mitchell};
inline constexpr WrapMode kAllWraps[] = {WrapMode::clamp, WrapMode::repeat, WrapMode::mirror};

}  // namespace texproc::test
