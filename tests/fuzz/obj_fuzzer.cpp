// libFuzzer target for the OBJ mesh reader (src/scene/obj_mesh.cpp): any bytes
// must either give a closed solid or an InputError naming the scene's field.
// Another exception, a crash, undefined behaviour, a huge allocation or a
// hang is a finding. Built only with -DSPHCLIP_FUZZ=ON and clang; run with
// tests/fuzz/run_fuzzer.sh obj SECONDS.

#include "scene/input_error.hpp"
#include "scene/obj_mesh.hpp"

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string_view>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string_view text(reinterpret_cast<const char*>(data), size);
    std::shared_ptr<const sph::TriangleMesh> mesh;
    try {
        mesh = sph::parse_obj_mesh(text, "fuzz.obj", 1, sph::Vec<3>(0), "fuzz.json", "mesh");
    } catch (const sph::InputError& e) {
        if (e.file != "fuzz.json" || e.field != "mesh") {
            std::fprintf(stderr, "an InputError that names another file or field: %s\n", e.what());
            std::abort();
        }
        return 0; // the expected answer to a bad mesh
    }
    // A mesh that loads is a solid with finite vertices, every triangle
    // naming vertices it has.
    const auto& vertices = mesh->vertices();
    for (const auto& v : vertices)
        for (int a = 0; a < 3; ++a)
            if (!std::isfinite(v[a])) {
                std::fprintf(stderr, "a loaded mesh has a non-finite vertex\n");
                std::abort();
            }
    for (const auto& t : mesh->triangles())
        for (const auto corner : t)
            if (corner >= vertices.size()) {
                std::fprintf(stderr, "a triangle names vertex %u of %zu\n", unsigned(corner),
                             vertices.size());
                std::abort();
            }
    return 0;
}
