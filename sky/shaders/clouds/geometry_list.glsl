// The trace cells over a host's geometry whose pixels are marched on their own rays to it
// (CloudOwnRayWeight): clouds/geometry_list.frag lists them, clouds/geometry_march.* draw a
// block x block square over each, from the glDrawArraysIndirect command at the block's start.
layout(std430, binding = kCloudGeometryListBinding) buffer CloudGeometryList {
    uint geometry_vertices;   // the draw's vertex count: 6 per cell found
    uint geometry_instances;  // 1
    uint geometry_first;      // 0
    uint geometry_base_instance;  // 0
    uint geometry_capacity;   // the cells the list holds: every trace cell (checked all the same)
    uint geometry_unused[3];
    uint geometry_cells[];    // x | y << 16
};
