#pragma once
// Searches whose references are not simply the points themselves: periodic boxes (the points
// plus their images across the periodic faces) and queries against a separate reference set.
// Both run any backend on one local point set (queries first, references after, as
// SearchOptions::queries has it) and map the ids of its rows back.
#include <cstdint>
#include <vector>

#include "horizon/search.hpp"

namespace horizon::detail {

/// The rows of the first `queries` points of `local` searched with `options` (its box ignored),
/// each id j mapped to id_of[j] (dropped when < 0; half lists keep id_of[j] > i). Ids j below
/// `ascending_below` map in ascending order; the rest are sorted and merged in (sort_rows).
NeighborList search_mapped(PointView local, std::size_t queries, const point_id* id_of,
                           std::size_t ascending_below, const SearchOptions& options, SearchStats& stats);

/// `points` in the periodic box options.box (validated: clear errors naming the axis or point)
/// on `backend` (resolved: not automatic).
NeighborList search_periodic(PointView points, Backend backend, const SearchOptions& options, SearchStats& stats);

/// `queries` against `references`, periodic when options.box says so.
NeighborList search_references(PointView queries, PointView references, const SearchOptions& options,
                               SearchStats& stats);

/// Checks options.box against the dimension and the horizon: clear errors naming the axis.
void validate_box_shape(const SearchOptions& options, int dims);

/// Throws the error for `which` point `id` at xyz when it lies outside options.box.
void throw_outside_box(const char* which, std::int64_t id, const double* xyz, int dims, const SearchOptions& options);

/// Checks options.box against the points and the horizon: clear errors naming the axis, or the
/// first point outside (`which` and its index, or ids[index] when given). On `threads` (0: all).
void validate_box(PointView points, const SearchOptions& options, const char* which,
                  const std::int64_t* ids = nullptr, int threads = 0);

/// The images of `points` that can be within the horizon of a point of the box: each point
/// within the horizon of a periodic face, shifted by the period across it (corners: every
/// combination). Appended to `local`, their originals' indices (+ `id_base`) to `id_of`.
void append_images(PointView points, const SearchOptions& options, PointSet& local, std::vector<point_id>& id_of,
                   point_id id_base);

/// Whether options.box makes any axis periodic.
bool is_periodic(const SearchOptions& options);

}  // namespace horizon::detail
