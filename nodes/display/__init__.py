"""Display: how geometry is drawn (colour, line width), text tags and plots of numbers."""
