#include "render/lighting.hpp"

#include <embedded_shaders.hpp>
#include <glm/gtc/type_ptr.hpp>

namespace sph {

Lighting key_light(const Camera& camera, const glm::dvec3& up_world, const Palette& palette) {
    Lighting l;
    l.sky = palette.sky;
    l.ground = palette.ground;
    l.to_light = glm::normalize(l.to_light);
    if (camera.orthographic)
        return l;
    const glm::mat3 rotation(camera.view);
    const glm::vec3 up = glm::normalize(glm::vec3(up_world));
    // The camera's right and backward (towards the viewer) in the world,
    // made horizontal.
    const glm::mat3 world_from_view = glm::transpose(rotation);
    glm::vec3 right = world_from_view * glm::vec3(1, 0, 0);
    glm::vec3 back = world_from_view * glm::vec3(0, 0, 1);
    right -= glm::dot(right, up) * up;
    back -= glm::dot(back, up) * up;
    right = glm::length(right) > 1e-6f ? glm::normalize(right) : glm::vec3(0);
    back = glm::length(back) > 1e-6f ? glm::normalize(back) : glm::vec3(0);
    const glm::vec3 world = glm::normalize(up - 0.55f * right + 0.35f * back);
    l.to_light = glm::normalize(rotation * world);
    l.up = glm::normalize(rotation * up);
    return l;
}

std::string lighting_source(bool shadows) {
    return (shadows ? "#define SHADOWS\n" : "") + std::string(shaders::lighting);
}

void set_lighting(GLuint program, const Lighting& l) {
    auto at = [program](const char* name) {
        return glGetUniformLocation(program, name);
    };
    glUniform3fv(at("u_light"), 1, glm::value_ptr(l.to_light));
    glUniform3fv(at("u_up"), 1, glm::value_ptr(l.up));
    glUniform3fv(at("u_sky"), 1, glm::value_ptr(l.sky));
    glUniform3fv(at("u_ground"), 1, glm::value_ptr(l.ground));
    glUniform1i(at("u_shadows"), l.shadows);
    glUniform1i(at("u_shadow_map"), shadow_map_unit);
    glUniformMatrix4fv(at("u_shadow_from_view"), 1, GL_FALSE, glm::value_ptr(l.shadow_from_view));
    glUniform1f(at("u_shadow_softness"), l.shadow_softness);
    glUniform1f(at("u_shadow_offset"), l.shadow_offset);
}

} // namespace sph
