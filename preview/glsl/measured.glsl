// Measured table as a 3D texture (preview/renderer.cc uploads it): s = phi_d / pi (repeat),
// t = theta_d / (pi/2), r = theta_h coordinate / n_theta_h (both clamp to edge), i.e. the
// table's index coordinate u over n, so linear filtering interpolates between CELL CENTRES
// exactly as Table::LookupTrilinear (core/table.h); it is done in the shader with float weights
// (texel_filter.glsl), not by the texture unit. Texels hold (rgb * valid, valid): the filtered
// alpha is the weight of the valid neighbours and dividing by it drops invalid cells and
// renormalizes.
// TABLE_SQRT_THETA_H selects MERL's theta_h index N sqrt(theta_h / (pi/2)) over the linear one.
uniform sampler3D uTable;
// brdfit-requires: preview/glsl/halfdiff.glsl
// brdfit-requires: preview/glsl/texel_filter.glsl

vec3 EvalBrdf(const in BrdfGeometry g) {
  vec3 a = brdfit_HalfDiff(g);
  float th = a.x / (0.5 * PI);
#if TABLE_SQRT_THETA_H
  th = sqrt(th);
#endif
  vec4 t = brdfit_TrilinearRepeatS(uTable, vec3(a.z / PI, a.y / (0.5 * PI), th));
  return t.a > 0.0 ? t.rgb / t.a : vec3(0.0);  // no valid neighbour: black (docs/preview.md)
}
