// The shared scene triangles (renderer/services/scene_triangles.h). Define
// SCENE_TRIANGLES_BINDING and SCENE_MATERIALS_BINDING before including.
struct SceneTriangle {
    vec4 p0;      // xyz world; w = material index
    vec4 p1;      // xyz; w = draw index
    vec4 p2;      // xyz; w = triangle within the draw
    vec4 normal;  // xyz unit geometric normal; w = area
};
struct SceneTriangleMaterial {
    vec4 baseColor;
    vec4 emission;  // rgb radiance; w = double sided
    vec4 params;    // metallic, roughness, specular, alpha cutoff (<0 opaque)
};
layout(std430, binding = SCENE_TRIANGLES_BINDING) readonly buffer SceneTriangleBuffer { SceneTriangle u_sceneTriangles[]; };
layout(std430, binding = SCENE_MATERIALS_BINDING) readonly buffer SceneMaterialBuffer { SceneTriangleMaterial u_sceneMaterials[]; };
