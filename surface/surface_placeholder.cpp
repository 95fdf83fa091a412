// Replaced by the surfacing stage.
