// One triangle over the whole viewport, from the vertex index alone (no
// buffer): the backdrop's and the ambient occlusion's passes.
out vec2 v_uv; // 0..1 over the viewport

void main() {
    vec2 corner = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2));
    v_uv = corner;
    gl_Position = vec4(2.0 * corner - 1.0, 0.0, 1.0);
}
