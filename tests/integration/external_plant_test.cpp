// A plant from outside (plant.type external) in a run: filled in next.
