"""Display: how geometry is drawn (colour, line width), text tags and plots of numbers."""

#: The modules holding this palette's node types (read by engine.registry; imported on demand).
NODE_TYPES = ("preview", "plot")
#: The modules defining value types this palette adds.
VALUE_TYPES = ("hints",)
