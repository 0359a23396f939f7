# error: python_no_project.py:1:1: 'python_no_project.py' defines no rfc.Project
# hint: create one at module level: project = rfc.Project('Name', ...)
import rfc
from parts import QuaternionToEuler

