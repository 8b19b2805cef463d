"""The block lower-triangular rate solver of the compiled mechanism's evaluators."""

import numpy as np

from linkage_sym.codegen.blocks import BlockSystem



