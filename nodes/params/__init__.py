"""Parameters: the values a designer sets by hand (sliders, toggles, panels, points)."""
