// Copyright (c) 2026 CGAL Spherical Parameterization contributors.
// This file is part of CGAL Spherical Parameterization, a package in CGAL's style (www.cgal.org).
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s)     : CGAL Spherical Parameterization contributors

// Two independent computations at the same time (CGAL::Parallel_tag with TBB), or one after the other. Each is done
// by one thread exactly as it would be alone, so the results are the same to the last bit either way: stage 3's
// parallelism does not change its iterates, and with them the outcome on a hard mesh. (Splitting a sum over the
// vertices between threads would change its rounding, and the paths of the Newton steps are sensitive to that.)

#ifndef CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_SIDE_BY_SIDE_H
#define CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_SIDE_BY_SIDE_H

#ifdef CGAL_LINKED_WITH_TBB
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>
#endif

#include <cstddef>

namespace CGAL {
namespace Spherical_parameterization {
namespace internal {

template <class First, class Second>
void side_by_side(bool parallel, const First& first, const Second& second)
{
#ifdef CGAL_LINKED_WITH_TBB
  if(parallel)
  {
    tbb::parallel_invoke(first, second);
    return;
  }
#else
  (void)parallel;
#endif
  first();
  second();
}

// A line-search trial: its test (which it returns) and its merit, which the acceptance needs only when the test
// passes. With `parallel` the merit is computed beside the test (wasted when the test fails); otherwise after it.
template <class Test, class Merit>
bool test_with_merit(bool parallel, const Test& test, const Merit& merit)
{
  bool passed = false;
  if(parallel)
  {
    side_by_side(true, [&]() { passed = test(); }, merit);
    return passed;
  }
  passed = test();
  if(passed)
    merit();
  return passed;
}

// `body(begin, end)` over the blocks of [0, count): with `parallel` (TBB) on several threads at once, so that the body
// may only write what belongs to its block (per-face terms, later added up in order by one thread: the sums and with
// them the results are the same to the last bit either way); otherwise over the whole range in one call.
template <class Body>
void for_each_block(bool parallel, std::size_t count, std::size_t grain, const Body& body)
{
#ifdef CGAL_LINKED_WITH_TBB
  if(parallel)
  {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, count, grain),
                      [&](const tbb::blocked_range<std::size_t>& range) { body(range.begin(), range.end()); });
    return;
  }
#else
  (void)grain;
  (void)parallel;
#endif
  body(std::size_t(0), count);
}

} // namespace internal
} // namespace Spherical_parameterization
} // namespace CGAL

#endif // CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_SIDE_BY_SIDE_H
