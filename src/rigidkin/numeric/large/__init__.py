"""Large systems: trees of pinned bodies by the articulated-body algorithm (numpy or C), the projected
model of large 3D systems and its linearisation about a motion, and the route that picks them."""
