#pragma once
// Small operations on meshes shared by the glTF loader and the scene builder.
#include <vector>

#include "penumbra/scene.h"

namespace penumbra {

// Object-space bounds of the vertices (invalid for an empty mesh).
Aabb computeBounds(const std::vector<Vertex>& vertices);

// Gives every triangle its own three vertices with the face normal, as glTF requires when NORMAL is
// missing ("client implementations MUST calculate flat normals"). Degenerate triangles get +Y.
void generateFlatNormals(Mesh& mesh);

// Bounds of every instance in world space, and of the whole scene.
void computeWorldBounds(Scene& scene);

}  // namespace penumbra
