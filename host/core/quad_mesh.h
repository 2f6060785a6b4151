#pragma once

#include <OpenMesh/Core/Mesh/PolyMesh_ArrayKernelT.hh>

namespace mcquad {

struct QuadMeshTraits : public OpenMesh::DefaultTraits {
  using Point = OpenMesh::Vec3d;
  using Normal = OpenMesh::Vec3d;
  VertexAttributes(OpenMesh::Attributes::Status);
  FaceAttributes(OpenMesh::Attributes::Status);
  EdgeAttributes(OpenMesh::Attributes::Status);
  HalfedgeAttributes(OpenMesh::Attributes::Status);
};

//! The host-side mesh used for topology work, refinement and writing.
using QuadMesh = OpenMesh::PolyMesh_ArrayKernelT<QuadMeshTraits>;

}  // namespace mcquad
