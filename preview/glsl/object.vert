// A Three.js-style vertex stage (as mebiusbox 2018's pbr_vert.glsl) in GLSL 330: view-space
// position and normal.
// For an analytic sphere the mesh is a bounding proxy; the fragment stage intersects the sphere.
layout(location = 0) in vec3 position;
layout(location = 1) in vec3 normal;
uniform mat4 uModelView;
uniform mat4 uProjection;
uniform mat3 uNormalMatrix;  // transpose(inverse(modelView)) (Three.js normalMatrix)
out vec3 vViewPosition;
out vec3 vNormal;
void main() {
  vec4 mvPosition = uModelView * vec4(position, 1.0);
  gl_Position = uProjection * mvPosition;
  vViewPosition = -mvPosition.xyz;
  vNormal = uNormalMatrix * normal;
}
