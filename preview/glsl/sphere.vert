// Screen rectangle (NDC) that bounds an analytic sphere's projection, computed on the CPU;
// the fragment stage intersects the sphere per pixel. Two triangles from gl_VertexID.
uniform vec4 uRect;  // xmin, ymin, xmax, ymax in NDC
void main() {
  const vec2 corner[6] = vec2[6](vec2(0, 0), vec2(1, 0), vec2(1, 1), vec2(0, 0), vec2(1, 1),
                                 vec2(0, 1));
  vec2 c = corner[gl_VertexID];
  gl_Position = vec4(mix(uRect.xy, uRect.zw, c), 0.0, 1.0);
}
