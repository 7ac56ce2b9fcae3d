// Normals of the visible surface for fragment shaders: the triangle's plane and a compact encoding.
#ifndef PENUMBRA_SURFACE_NORMALS_GLSL
#define PENUMBRA_SURFACE_NORMALS_GLSL

// The triangle's normal from the screen derivatives of the position, turned to the side of the shading
// normal; the shading normal where the derivatives are degenerate. Call in uniform control flow.
vec3 geometricNormal(vec3 wsPosition, vec3 wsShadingNormal) {
    vec3 n = cross(dFdx(wsPosition), dFdy(wsPosition));
    float length2 = dot(n, n);
    if (!(length2 > 1e-30)) return wsShadingNormal;
    n *= inversesqrt(length2);
    return dot(n, wsShadingNormal) < 0.0 ? -n : n;
}

// Octahedral encoding of a unit vector in two components (Cigolle et al. 2014), for normal targets.
vec2 octEncode(vec3 n) {
    n /= abs(n.x) + abs(n.y) + abs(n.z);
    vec2 e = n.xy;
    if (n.z < 0.0) e = (1.0 - abs(n.yx)) * vec2(n.x >= 0.0 ? 1.0 : -1.0, n.y >= 0.0 ? 1.0 : -1.0);
    return e;
}
vec3 octDecode(vec2 e) {
    vec3 n = vec3(e, 1.0 - abs(e.x) - abs(e.y));
    if (n.z < 0.0) n.xy = (1.0 - abs(n.yx)) * vec2(n.x >= 0.0 ? 1.0 : -1.0, n.y >= 0.0 ? 1.0 : -1.0);
    return normalize(n);
}

#endif
