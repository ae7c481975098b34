// Linear texture filtering in the shader, with float weights: the same interpolation as
// GL_LINEAR (OpenGL 4.6 core spec, section 8.14.2, eqs. 8.9-8.11: i0 = floor(u N - 1/2),
// alpha = frac(u N - 1/2), the result sum over the 2^d corners of the products of the weights
// (1 - alpha) and alpha), but the weights are not quantized. Hardware filtering may compute them
// with as few as 8 fractional bits (NVIDIA does), so a table whose cells differ by decades, or
// whose validity weight is divided out, differs from the CPU evaluators (Table::LookupTrilinear,
// factor/factor_eval.h) by up to a percent there; this twin matches them to float precision on
// every conformant driver. texelFetch reads one texel with no filtering; the wrap modes are
// applied to the integer index here (repeat: modulo N; clamp to edge: to [0, N - 1]).
// GLSL leaves % undefined for a negative operand (GLSL 3.30, section 5.9), so a negative index
// is wrapped from its mirror image -i - 1 >= 0.
int brdfit_WrapIndex(int i, int n, bool repeat) {
  if (!repeat) return clamp(i, 0, n - 1);
  return i >= 0 ? i % n : n - 1 - (-i - 1) % n;
}

// The weights are applied as the spec's sum of products, every term >= 0: mix(a, b, t), often
// evaluated as a + t (b - a), cancels where a texel is decades above its neighbour and the
// result is small (a specular peak beside the body reflection).

// 2D: uv in texture coordinates; rows (t) repeat when repeat_t, columns always clamp.
vec4 brdfit_Bilinear(sampler2D tex, vec2 uv, bool repeat_t) {
  ivec2 n = textureSize(tex, 0);
  vec2 x = uv * vec2(n) - 0.5;
  vec2 x0 = floor(x);
  vec2 a = x - x0, b = 1.0 - a;
  ivec2 i0 = ivec2(x0);
  int s0 = brdfit_WrapIndex(i0.x, n.x, false), s1 = brdfit_WrapIndex(i0.x + 1, n.x, false);
  int t0 = brdfit_WrapIndex(i0.y, n.y, repeat_t), t1 = brdfit_WrapIndex(i0.y + 1, n.y, repeat_t);
  return b.x * b.y * texelFetch(tex, ivec2(s0, t0), 0) +
         a.x * b.y * texelFetch(tex, ivec2(s1, t0), 0) +
         b.x * a.y * texelFetch(tex, ivec2(s0, t1), 0) +
         a.x * a.y * texelFetch(tex, ivec2(s1, t1), 0);
}

// Two texels of a row of a 3D texture, weighted by ws0 and ws1.
vec4 brdfit_RowPair(sampler3D tex, int s0, int s1, int t, int r, float ws0, float ws1) {
  return ws0 * texelFetch(tex, ivec3(s0, t, r), 0) + ws1 * texelFetch(tex, ivec3(s1, t, r), 0);
}

// 3D: s repeats, t and r clamp to edge (the measured table's layout, preview/renderer.cc).
vec4 brdfit_TrilinearRepeatS(sampler3D tex, vec3 str) {
  ivec3 n = textureSize(tex, 0);
  vec3 x = str * vec3(n) - 0.5;
  vec3 x0 = floor(x);
  vec3 a = x - x0, b = 1.0 - a;
  ivec3 i0 = ivec3(x0);
  int s0 = brdfit_WrapIndex(i0.x, n.x, true), s1 = brdfit_WrapIndex(i0.x + 1, n.x, true);
  int t0 = brdfit_WrapIndex(i0.y, n.y, false), t1 = brdfit_WrapIndex(i0.y + 1, n.y, false);
  int r0 = brdfit_WrapIndex(i0.z, n.z, false), r1 = brdfit_WrapIndex(i0.z + 1, n.z, false);
  return brdfit_RowPair(tex, s0, s1, t0, r0, b.x * b.y * b.z, a.x * b.y * b.z) +
         brdfit_RowPair(tex, s0, s1, t1, r0, b.x * a.y * b.z, a.x * a.y * b.z) +
         brdfit_RowPair(tex, s0, s1, t0, r1, b.x * b.y * a.z, a.x * b.y * a.z) +
         brdfit_RowPair(tex, s0, s1, t1, r1, b.x * a.y * a.z, a.x * a.y * a.z);
}
