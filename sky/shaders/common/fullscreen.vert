// One triangle covering the viewport, from gl_VertexID alone (no vertex buffer).
void main() {
    vec2 position = vec2(float((gl_VertexID & 1) << 2) - 1.0, float((gl_VertexID & 2) << 1) - 1.0);
    gl_Position = vec4(position, 0.0, 1.0);
}
