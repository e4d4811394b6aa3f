// The output object's keys: where a run writes.
#include "scene/keys/scene_keys.hpp"

namespace sph {

const KeyTable<Scene::Output>& output_keys() {
    using S = Scene::Output;
    static const KeyTable<S> keys{
        {.path = "name",
         .field = &S::name,
         .doc = "Output folder under out/ when run has no --out: a relative path that stays "
                "inside out/ (not absolute, no \"..\").",
         .absent = "the scene file's name"},
    };
    return keys;
}

} // namespace sph
