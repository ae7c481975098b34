// Image files: 8-bit sRGB PNG (libpng) for display-referred images, 32-bit float OpenEXR for
// linear HDR radiance. Writers are atomic (io/atomic_file.h); readers throw InputError.
#pragma once

#include <filesystem>
#include <string>

#include "core/image.h"

namespace brdfit {

// Writes display-referred values (already tone mapped and encoded), clamped to [0, 1] and
// quantized by round(255 v), as an 8-bit RGBA PNG with the sRGB chunk.
void WritePng(const std::filesystem::path& path, const Image& display);
// The same PNG as WritePng, in memory (the file's bytes), e.g. for a data: URI. Throws
// std::runtime_error if libpng fails.
std::string EncodePng(const Image& display);
// Reads an 8-bit RGB/RGBA PNG into values k/255 (alpha 1 if absent).
Image ReadPng(const std::filesystem::path& path);

// Writes linear values as a 32-bit float RGBA OpenEXR (ZIP compression).
void WriteExr(const std::filesystem::path& path, const Image& linear);
Image ReadExr(const std::filesystem::path& path);

// Picks the writer from the extension: ".exr" -> linear EXR of `linear`, anything else -> PNG of
// `display`. Throws InputError for an unknown extension.
void WriteImageByExtension(const std::filesystem::path& path, const Image& linear,
                           const Image& display);

}  // namespace brdfit
