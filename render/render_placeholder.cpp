// Replaced by the render stage.
