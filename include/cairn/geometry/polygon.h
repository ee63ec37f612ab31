#pragma once
/// @file
/// Simple polygons in the plane: orientation, exact mass properties,
/// simplicity, point queries. A Polygon is a list of vertices; after
/// MakeCounterClockwise its signed area is positive and its outward edge
/// normals point to the right of each edge direction.

#include <array>
#include <optional>
#include <vector>

#include "cairn/core/types.h"

namespace cairn {

/// Vertices of a simple polygon, in order (no repeated closing vertex).
using Polygon = std::vector<Vector2>;

/// Signed area (positive when counter-clockwise), shoelace formula. (length²)
double SignedArea(const Polygon& poly);

/// Reverses the vertex order if the polygon is clockwise.
void MakeCounterClockwise(Polygon& poly);

/// Exact area properties of a simple polygon of unit density.
struct PolygonMass {
  double area = 0;          ///< length²
  Vector2 centroid{0, 0};   ///< length, world frame
  double polar_moment = 0;  ///< ∫ |r − centroid|² dA about the centroid (length⁴)
};

/// Exact area, centroid and polar second moment of a simple polygon (either
/// orientation), by Green's theorem over its edges. A part of mass m has
/// moment of inertia I = m · polar_moment / area about its centroid.
PolygonMass ComputePolygonMass(const Polygon& poly);

/// A pair of non-adjacent edges that touch or cross (edge i runs from vertex i
/// to vertex i+1), or two adjacent edges that fold back onto each other.
struct SelfIntersection {
  int edge_a = -1;
  int edge_b = -1;
};

/// The first self-intersection of the polygon's boundary, or nullopt when the
/// polygon is simple. Edges closer than `tol` (length) count as touching.
std::optional<SelfIntersection> FindSelfIntersection(const Polygon& poly, double tol);

/// Distance from p to the segment [a, b]. (length)
double DistanceToSegment(const Vector2& p, const Vector2& a, const Vector2& b);

/// Distance from p to the boundary of the polygon. (length)
double DistanceToBoundary(const Polygon& poly, const Vector2& p);

/// True when p is strictly inside the polygon (crossing-number test; points on
/// the boundary may go either way: combine with DistanceToBoundary).
bool ContainsPoint(const Polygon& poly, const Vector2& p);

/// Signed depth of p in the polygon: +distance to the boundary when inside,
/// −distance when outside. (length)
double SignedDepth(const Polygon& poly, const Vector2& p);

/// Axis-aligned bounding box corners (min, max).
std::pair<Vector2, Vector2> BoundingBox(const Polygon& poly);

/// Signed distance of p from the line through a and b, positive on its left
/// (length; 0 when a = b).
double LineSide(const Vector2& a, const Vector2& b, const Vector2& p);

/// True when segments [a0, a1] and [b0, b1] cross properly with margin `tol`:
/// each one's endpoints lie on opposite sides of the other's line, farther than
/// tol (length) from it.
bool SegmentsCrossProperly(const Vector2& a0, const Vector2& a1, const Vector2& b0,
                           const Vector2& b1, double tol);

/// A point inside both counter-clockwise polygons at a depth of more than
/// `tol` (length), or nullopt when they only touch (within tol) or are apart:
/// a vertex of one deep inside the other, two edges crossing properly, or, for
/// coincident shapes, a point just inside an edge midpoint of one lying deep
/// inside the other.
std::optional<Vector2> FindOverlap(const Polygon& a, const Polygon& b, double tol);

/// The triangles of a simple counter-clockwise polygon, as vertex index
/// triples (counter-clockwise), by ear clipping: O(n²) for n vertices.
/// Vertices on a straight line (turning by less than `tol`, length, off the
/// line through their neighbours) are passed over, so no triangle is a
/// sliver; their union is the polygon. Empty when no ear can be found (a
/// polygon that is not simple).
std::vector<std::array<int, 3>> Triangulate(const Polygon& ccw_poly, double tol);

/// Outward unit normal of edge i (from vertex i to i+1) of a counter-clockwise
/// polygon.
Vector2 EdgeNormal(const Polygon& ccw_poly, int i);

}  // namespace cairn
