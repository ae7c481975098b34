// Atomic output: every writer writes to a temporary file in the destination's folder and
// renames it over the destination only when the write completed. A crash or an exception
// never leaves a half-written result under the final name.
#pragma once

#include <cstddef>
#include <filesystem>
#include <functional>
#include <string>

namespace brdfit {

// Calls write(tmp_path), then renames tmp_path to dest. If write throws, the temporary file is
// removed and the exception propagates; dest is left as it was. Throws OutputError if dest is
// a directory or the rename fails.
void WriteFileAtomically(const std::filesystem::path& dest,
                         const std::function<void(const std::filesystem::path& tmp)>& write);

// Writes bytes atomically: every write and the close checked (a full disk or an I/O error is
// an OutputError naming dest, with the system's reason), then renamed into place.
void WriteBytesAtomically(const std::filesystem::path& dest, const void* data, std::size_t size);
void WriteTextAtomically(const std::filesystem::path& dest, const std::string& contents);

// Two files that belong together (a .gltf and the .bin it names): both are written to
// temporaries before either is renamed, second first, so a failed or refused write leaves both
// destinations as they were.
void WriteTwoFilesAtomically(const std::filesystem::path& first, const std::string& first_bytes,
                             const std::filesystem::path& second, const void* second_data,
                             std::size_t second_size);

}  // namespace brdfit
