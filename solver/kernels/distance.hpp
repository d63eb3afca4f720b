#pragma once
// Umbrella header of the contact distance kernels: squared distances between closed primitives,
// their classification by closest sub-primitives, and gradients and Hessians.

#include "solver/kernels/distance_type.hpp"
#include "solver/kernels/edge_edge_distance.hpp"
#include "solver/kernels/line_line_distance.hpp"
#include "solver/kernels/point_edge_distance.hpp"
#include "solver/kernels/point_line_distance.hpp"
#include "solver/kernels/point_plane_distance.hpp"
#include "solver/kernels/point_point_distance.hpp"
#include "solver/kernels/point_triangle_distance.hpp"
