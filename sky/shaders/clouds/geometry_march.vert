// Two triangles over the block x block pixels of each cell geometry_list.frag listed (none past
// the list's capacity).
void main() {
    uint i = uint(gl_VertexID) / 6u;
    uint p = i < geometry_capacity ? geometry_cells[i] : 0u;
    const ivec2 kCorners[6] =
        ivec2[6](ivec2(0, 0), ivec2(1, 0), ivec2(0, 1), ivec2(0, 1), ivec2(1, 0), ivec2(1, 1));
    ivec2 corner = (ivec2(int(p & 0xffffu), int(p >> 16)) + kCorners[gl_VertexID % 6]) * block;
    vec2 ndc = 2.0 * vec2(corner) / vec2(output_size) - 1.0;
    gl_Position = i < geometry_capacity ? vec4(ndc, 0.0, 1.0) : vec4(2.0, 2.0, 0.0, 1.0);
}
