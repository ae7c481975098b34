#include "export/blender_script.h"

#include <fmt/core.h>

#include "export/comment_text.h"

namespace brdfit::exports {

namespace {

// Printable ASCII for a '#' comment line.
std::string PythonComment(const std::string& s) {
  return "# " + CommentText(s) + "\n";
}

std::string Tuple3(const Rgb& v) {
  return fmt::format("({:.9g}, {:.9g}, {:.9g})", v[0], v[1], v[2]);
}

// The fixed part of the script: materials from the constants above it, the scene, the render.
constexpr const char* kScriptBody = R"PY(
import argparse
import math
import os
import sys

import bpy
from mathutils import Vector

LIGHT_TOWARDS = (1.0, 1.0, 1.0)  # direction from the sphere towards the sun
IRRADIANCE = 3.0  # W/m^2 on a surface facing the sun (Cycles' sun strength)


def rgba(c):
    return (c[0], c[1], c[2], 1.0)


def node_of_type(tree, kind):
    return next(n for n in tree.nodes if n.type == kind)


def glossy_bsdf(tree, color, roughness):
    """Glossy BSDF, GGX: color D G1 G1 / (4 cos_i cos_o), alpha = roughness^2."""
    glossy = tree.nodes.new("ShaderNodeBsdfGlossy")
    glossy.distribution = "GGX"
    glossy.inputs["Color"].default_value = rgba(color)
    glossy.inputs["Roughness"].default_value = roughness
    return glossy.outputs["BSDF"]


def add_shader(tree, a, b):
    add = tree.nodes.new("ShaderNodeAddShader")
    tree.links.new(a, add.inputs[0])
    tree.links.new(b, add.inputs[1])
    return add.outputs["Shader"]


def body_bsdf(tree):
    """The fit's body. Diffuse BSDF: Lambert kd / pi at roughness 0, Fujii's Oren-Nayar
    kd (a + b s / t) above (Cycles' bsdf_oren_nayar.h). Principled BSDF with Specular 0 and
    Metallic 0 (no specular closure): Burley 2012's diffuse of base colour kd, roughness r."""
    if EXACT["body"] == "burley-2012":
        p = tree.nodes.new("ShaderNodeBsdfPrincipled")
        p.distribution = "GGX"
        p.inputs["Base Color"].default_value = rgba(EXACT["diffuse_color"])
        p.inputs["Roughness"].default_value = EXACT["body_roughness"]
        for name in ("Metallic", "Specular", "Specular Tint", "Subsurface", "Sheen", "Clearcoat",
                     "Transmission", "Anisotropic"):
            p.inputs[name].default_value = 0.0
        return p.outputs["BSDF"]
    diffuse = tree.nodes.new("ShaderNodeBsdfDiffuse")
    diffuse.inputs["Color"].default_value = rgba(EXACT["diffuse_color"])
    diffuse.inputs["Roughness"].default_value = EXACT["body_roughness"]
    return diffuse.outputs["BSDF"]


def exact_material():
    """The body (body_bsdf) + Glossy BSDF (GGX, no Fresnel) [+ a second one].

    f = body + ks D G / (4 cos_i cos_o) [+ ks2 D2 G2 / (4 cos_i cos_o)]."""
    mat = bpy.data.materials.new("brdfit-material")
    mat.use_nodes = True
    tree = mat.node_tree
    tree.nodes.clear()
    out = tree.nodes.new("ShaderNodeOutputMaterial")
    shader = add_shader(tree, body_bsdf(tree),
                        glossy_bsdf(tree, EXACT["glossy_color"], EXACT["roughness"]))
    if "second_glossy_color" in EXACT:
        # The fit's second lobe, added.
        shader = add_shader(tree, shader, glossy_bsdf(tree, EXACT["second_glossy_color"],
                                                      EXACT["second_roughness"]))
    tree.links.new(shader, out.inputs["Surface"])
    return mat


def principled_material():
    """Principled BSDF (Blender 3.4, GGX): approximate, see the header."""
    mat = bpy.data.materials.new("brdfit-principled")
    mat.use_nodes = True
    mat.use_fake_user = True
    p = node_of_type(mat.node_tree, "BSDF_PRINCIPLED")
    p.distribution = "GGX"
    p.inputs["Base Color"].default_value = rgba(PRINCIPLED["base_color"])
    p.inputs["Roughness"].default_value = PRINCIPLED["roughness"]
    p.inputs["Specular"].default_value = PRINCIPLED["specular"]
    p.inputs["Specular Tint"].default_value = PRINCIPLED["specular_tint"]
    p.inputs["Metallic"].default_value = PRINCIPLED["metallic"]
    for name in ("Subsurface", "Sheen", "Clearcoat", "Transmission", "Anisotropic"):
        p.inputs[name].default_value = 0.0
    return mat


def build_scene(material, o):
    for ob in list(bpy.data.objects):
        bpy.data.objects.remove(ob, do_unlink=True)
    scene = bpy.context.scene
    # Unit sphere, poles along y like brdfit's preview sphere; smooth-shaded 128 x 64 bands.
    bpy.ops.mesh.primitive_uv_sphere_add(segments=128, ring_count=64, radius=1.0)
    sphere = bpy.context.active_object
    sphere.name = "brdfit-sphere"
    sphere.rotation_euler = (math.pi / 2, 0.0, 0.0)
    bpy.ops.object.shade_smooth()
    sphere.data.materials.append(material)
    # Camera at (0, 0, 4) looking down -z with +y up (Blender's unrotated camera), 30 deg vertical.
    cam_data = bpy.data.cameras.new("brdfit-camera")
    cam_data.sensor_fit = "VERTICAL"
    cam_data.angle_y = math.radians(30.0)
    cam_data.clip_start = 0.1
    cam = bpy.data.objects.new("brdfit-camera", cam_data)
    cam.location = (0.0, 0.0, 4.0)
    scene.collection.objects.link(cam)
    scene.camera = cam
    # Sun: a delta directional light (angle 0) shining along -LIGHT_TOWARDS.
    sun_data = bpy.data.lights.new("brdfit-sun", type="SUN")
    sun_data.energy = IRRADIANCE
    sun_data.angle = 0.0
    sun = bpy.data.objects.new("brdfit-sun", sun_data)
    sun.rotation_euler = Vector(LIGHT_TOWARDS).to_track_quat("Z", "Y").to_euler()
    scene.collection.objects.link(sun)
    world = bpy.data.worlds.new("brdfit-world")
    world.use_nodes = True
    bg = node_of_type(world.node_tree, "BACKGROUND")
    bg.inputs["Color"].default_value = (0.0, 0.0, 0.0, 1.0)
    bg.inputs["Strength"].default_value = 0.0
    scene.world = world
    # Cycles on the CPU, direct light only (a convex sphere under a black world has no other
    # path), no denoiser, no dithering, linear to sRGB with the Standard view transform.
    scene.render.engine = "CYCLES"
    scene.cycles.device = "CPU"
    scene.cycles.samples = o.samples
    scene.cycles.seed = o.seed
    scene.cycles.use_adaptive_sampling = False
    scene.cycles.use_denoising = False
    scene.cycles.max_bounces = 0
    scene.cycles.pixel_filter_type = "BOX"
    scene.cycles.filter_width = 1.0
    scene.render.resolution_x = o.size
    scene.render.resolution_y = o.size
    scene.render.resolution_percentage = 100
    scene.render.film_transparent = False
    scene.render.dither_intensity = 0.0
    if o.threads > 0:
        scene.render.threads_mode = "FIXED"
        scene.render.threads = o.threads
    scene.display_settings.display_device = "sRGB"
    scene.view_settings.view_transform = "Standard"
    scene.view_settings.look = "None"
    scene.view_settings.exposure = 0.0
    scene.view_settings.gamma = 1.0
    scene.render.image_settings.file_format = "PNG"
    scene.render.image_settings.color_mode = "RGB"
    scene.render.image_settings.color_depth = "8"
    return scene


def main():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    ap = argparse.ArgumentParser(prog="blender -b --factory-startup -P this.py --")
    ap.add_argument("--material", choices=("exact", "principled"), default="exact")
    ap.add_argument("--render", help="write the Cycles render to this PNG")
    ap.add_argument("--size", type=int, default=256)
    ap.add_argument("--samples", type=int, default=16)
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--threads", type=int, default=0, help="0: Blender's default")
    ap.add_argument("--save", help="write the scene to this .blend")
    o = ap.parse_args(argv)
    exact, principled = exact_material(), principled_material()
    scene = build_scene(exact if o.material == "exact" else principled, o)
    if o.save:
        bpy.ops.wm.save_as_mainfile(filepath=os.path.abspath(o.save))
    if o.render:
        scene.render.filepath = os.path.abspath(o.render)
        bpy.ops.render.render(write_still=True)


main()
)PY";

}  // namespace

std::string BlenderScript(const BlenderMaterial& m, const Provenance& p) {
  std::string s;
  for (const std::string& line : p.Lines()) s += PythonComment(line);
  Provenance principled = p;
  principled.fidelity = m.principled_fidelity;
  s += PythonComment("material brdfit-principled (not on the sphere; --material principled): " +
                     principled.FidelityLine());
  s +=
      "#\n# brdfit-material (on the sphere): Add Shader(body, Glossy BSDF GGX)\n"
      "#   = body + ks D G1 G1 / (4 cos_i cos_o)  (Cycles 3.4: GGX, separable Smith); the body is\n"
      "#   a Diffuse BSDF (roughness 0: Lambert kd / pi; sigma: Fujii's Oren-Nayar) or, for\n"
      "#   burley-2012, a Principled BSDF with Specular 0 and Metallic 0 (Burley 2012 diffuse)\n"
      "#   (+ a second Glossy BSDF when EXACT has second_glossy_color: the fit's second lobe)\n"
      "# brdfit-principled: Principled BSDF (GGX), roughness sqrt(alpha), metallic 0 with base "
      "colour\n"
      "#   kd and cspec0 = 0.08 specular ((1 - tint) + tint kd / lum(kd)) nearest to ks, or\n"
      "#   metallic 1 with base colour ks when that is nearer\n"
      "# Render: blender -b --factory-startup --python-exit-code 1 -P this.py -- --render out.png\n"
      "#   [--material exact|principled] [--size 256] [--samples 16] [--save scene.blend]\n"
      "# (docs/exports.md, \"Blender\")\n";
  const char* body = m.body == Body::kOrenNayarFujii ? "oren-nayar-fujii"
                     : m.body == Body::kBurley2012   ? "burley-2012"
                                                     : "lambert";
  s += fmt::format("\nEXACT = {{\"body\": \"{}\", \"body_roughness\": {:.9g},\n", body,
                   m.body_roughness);
  s += fmt::format("         \"diffuse_color\": {}, \"glossy_color\": {}, \"roughness\": {:.9g}",
                   Tuple3(m.diffuse_color), Tuple3(m.glossy_color), m.roughness);
  if (m.second) {
    s += fmt::format(",\n         \"second_glossy_color\": {}, \"second_roughness\": {:.9g}",
                     Tuple3(m.second->glossy_color), m.second->roughness);
  }
  s += "}\n";
  s += fmt::format(
      "PRINCIPLED = {{\"base_color\": {}, \"metallic\": {:.9g}, \"roughness\": {:.9g},\n"
      "              \"specular\": {:.9g}, \"specular_tint\": {:.9g}}}  # cspec0 = {}\n",
      Tuple3(m.base_color), m.metallic, m.roughness, m.specular, m.specular_tint,
      Tuple3(m.principled_f0));
  s += kScriptBody;
  return s;
}

}  // namespace brdfit::exports
