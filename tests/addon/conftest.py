import os
import sys

# The helper that imports the add-on's bpy-free modules sits beside the tests.
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
