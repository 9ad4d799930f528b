//! State names of the flexible tethered satellite, for every node count up to
//! [`MAX_NODES`]: the layout puts the sub-satellite first, then the nodes from the main
//! satellite outwards, so the names of N nodes are a prefix of this list.

/// Most tether nodes a flexible model may have (the length of the name list).
pub const MAX_NODES: usize = 32;

pub const NAMES: [&str; 6 + 4 * MAX_NODES] = [
    "xs", "ys", "theta", "vxs", "vys", "omega", "x1", "y1", "vx1", "vy1", "x2", "y2", "vx2", "vy2",
    "x3", "y3", "vx3", "vy3", "x4", "y4", "vx4", "vy4", "x5", "y5", "vx5", "vy5", "x6", "y6",
    "vx6", "vy6", "x7", "y7", "vx7", "vy7", "x8", "y8", "vx8", "vy8", "x9", "y9", "vx9", "vy9",
    "x10", "y10", "vx10", "vy10", "x11", "y11", "vx11", "vy11", "x12", "y12", "vx12", "vy12",
    "x13", "y13", "vx13", "vy13", "x14", "y14", "vx14", "vy14", "x15", "y15", "vx15", "vy15",
    "x16", "y16", "vx16", "vy16", "x17", "y17", "vx17", "vy17", "x18", "y18", "vx18", "vy18",
    "x19", "y19", "vx19", "vy19", "x20", "y20", "vx20", "vy20", "x21", "y21", "vx21", "vy21",
    "x22", "y22", "vx22", "vy22", "x23", "y23", "vx23", "vy23", "x24", "y24", "vx24", "vy24",
    "x25", "y25", "vx25", "vy25", "x26", "y26", "vx26", "vy26", "x27", "y27", "vx27", "vy27",
    "x28", "y28", "vx28", "vy28", "x29", "y29", "vx29", "vy29", "x30", "y30", "vx30", "vy30",
    "x31", "y31", "vx31", "vy31", "x32", "y32", "vx32", "vy32",
];
