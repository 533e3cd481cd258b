"""The keys: both keys projected into the drawing plane, and the hints read and checked."""
