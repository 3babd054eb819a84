// A fixture for the test cosim.rooms_catches: a source outside every room.
