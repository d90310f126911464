"""Transform: move, rotate, scale, mirror, orient and array any geometry."""
