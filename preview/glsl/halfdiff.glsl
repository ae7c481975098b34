// Twin of ToHalfDiff (models/geometry.h), Rusinkiewicz 1998. Angles by atan2 of components
// rather than acos, which loses half the float digits near 0.
vec3 brdfit_HalfDiff(const in BrdfGeometry g) {
  vec3 h = g.h;
  float theta_h = atan(sqrt(g.sin2_h), h.z);
  float phi_h = g.sin2_h > 0.0 ? atan(h.y, h.x) : 0.0;
  float c = cos(-phi_h), s = sin(-phi_h);
  vec3 d = vec3(c * g.wi.x - s * g.wi.y, s * g.wi.x + c * g.wi.y, g.wi.z);  // RotateZ(wi, -phi_h)
  c = cos(-theta_h);
  s = sin(-theta_h);
  d = vec3(c * d.x + s * d.z, d.y, -s * d.x + c * d.z);  // RotateY(., -theta_h)
  float theta_d = atan(length(d.xy), d.z);
  float phi_d = (d.x == 0.0 && d.y == 0.0) ? 0.0 : atan(d.y, d.x);
  if (phi_d < 0.0) phi_d += PI;
  return vec3(theta_h, theta_d, phi_d);
}
