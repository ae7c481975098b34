// LeakSanitizer: Mesa's llvmpipe and LLVM keep process-lifetime allocations (compiled shader
// code, driver singletons) that are not ours to free. Suppressed by library name only; leaks
// in brdfit code are still reported.
extern "C" const char* __lsan_default_suppressions() {
  return "leak:libLLVM\nleak:libgallium\nleak:swrast_dri\nleak:libEGL_mesa\nleak:libglapi\n"
         "leak:libdrm\nleak:dri_\n";
}
