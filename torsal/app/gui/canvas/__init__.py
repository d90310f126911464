"""The node canvas: a QGraphicsView showing the engine's graph."""
