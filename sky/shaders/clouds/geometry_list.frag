// One invocation per trace cell: lists the cell when a pixel of it lies on a host's geometry
// where the cells around disagree about the clouds in front of it (CloudOwnRayWeight > 0). Whether
// the cell holds geometry at all is found first, and the rest is done in a loop that a cell
// without any skips (llvmpipe runs both sides of a branch under a mask, but leaves a loop as soon
// as no invocation is left in it).
bool CloudGeometryAt(ivec2 pixel) {
    return all(lessThan(pixel, output_size)) && SceneDistanceKm(pixel) > 0.0;
}

void main() {
    ivec2 cell = ivec2(gl_FragCoord.xy);
    int pixels = block * block;
    bool geometry = false;
    for (int i = 0; i < pixels; ++i) {
        geometry = geometry || CloudGeometryAt(cell * block + ivec2(i % block, i / block));
    }
    bool listed = false;
    CloudCellNeighbourhood cells;
    for (int i = 0; i < (geometry ? pixels : 0) && !listed; ++i) {
        if (i == 0) cells = CloudCellNeighbourhoodAt(cell);
        ivec2 pixel = cell * block + ivec2(i % block, i / block);
        float distance_km = all(lessThan(pixel, output_size)) ? SceneDistanceKm(pixel) : -1.0;
        listed = distance_km > 0.0 && CloudOwnRayWeight(cells, pixel, distance_km) > 0.0;
    }
    if (listed) {
        uint i = atomicAdd(geometry_vertices, 6u) / 6u;
        if (i < geometry_capacity) geometry_cells[i] = uint(cell.x) | (uint(cell.y) << 16);
    }
}
