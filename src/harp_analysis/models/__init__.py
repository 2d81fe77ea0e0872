"""Models of the world a flight meets: the atmospheres, drag laws, projectiles, sites, the launch
every engine flies and the trajectory table every engine returns."""
