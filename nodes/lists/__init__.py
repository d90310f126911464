"""Lists: pick, reorder, cull and restructure lists and data trees."""
