#include "io/unique_keys_json.h"

#include <set>
#include <vector>

#include "core/error.h"
#include "io/input_file.h"

namespace brdfit {

namespace {

using nlohmann::json;

// One open object or array: the keys seen (objects), the key or index of the member being read.
struct Frame {
  bool object = false;
  std::set<std::string> keys;
  std::string key;
  std::size_t index = 0;
};

// "materials.gold", "objects[2]": where the innermost open object sits.
std::string PathOf(const std::vector<Frame>& frames) {
  std::string path;
  for (std::size_t i = 0; i + 1 < frames.size(); ++i) {
    if (frames[i].object) {
      path += (path.empty() ? "" : ".") + PrintableExcerpt(frames[i].key, 64);
    } else {
      path += "[" + std::to_string(frames[i].index) + "]";
    }
  }
  return path.empty() ? "the top-level object" : path;
}

}  // namespace

json ParseJsonUniqueKeys(const std::string& text, const std::filesystem::path& file) {
  std::vector<Frame> frames;
  // An element of an array is done: the next one has the next index.
  auto element_done = [&] {
    if (!frames.empty() && !frames.back().object) ++frames.back().index;
  };
  const json::parser_callback_t check = [&](int, json::parse_event_t event, json& parsed) {
    switch (event) {
      case json::parse_event_t::object_start:
      case json::parse_event_t::array_start:
        frames.push_back({event == json::parse_event_t::object_start, {}, {}, 0});
        break;
      case json::parse_event_t::key: {
        const std::string key = parsed.get<std::string>();
        if (!frames.back().keys.insert(key).second) {
          throw InputError(
              file, "duplicate key '" + PrintableExcerpt(key, 64) + "' in " + PathOf(frames));
        }
        frames.back().key = key;
        break;
      }
      case json::parse_event_t::object_end:
      case json::parse_event_t::array_end:
        frames.pop_back();
        element_done();
        break;
      case json::parse_event_t::value:
        element_done();
        break;
    }
    return true;
  };
  return json::parse(text, check);
}

}  // namespace brdfit
