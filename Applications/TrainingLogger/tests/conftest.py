# SPDX-License-Identifier: BSD-3-Clause
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.dirname(HERE))  # the vis4gs_logger package, without installing
sys.path.insert(0, HERE)  # the mocks
