"""Measured data in: what test systems export, read and turned into quantities a model is
compared with. Universal-file dataset 58 functions (FRFs, spectra, order functions) in and
out (:mod:`.uff`), order cuts from CSV (:mod:`.ordercut`), a torsiograph's tooth-edge
timestamps (read by :mod:`.edges`) to angular speed, order amplitudes against speed and the
twist between two wheels (:mod:`.torsiograph`), and natural frequencies, damping ratios and mode shapes fitted
to measured FRFs (:mod:`.modal`); every file of a comparison read together, its channels matched
by name (:mod:`.reading`). Units are read from the files and checked (:mod:`.units`);
everything handed on is SI.

Uses no FE and no model: the stages that compare with a model or calibrate it take these
results.
"""

from .modal import ModalEstimate, estimate_modes, frf_matrix, mac, run_modal_fit
from .ordercut import read_curve_csv, read_order_cut_csv
from .reading import MeasuredOptions, read_measured
from .edges import read_edges_csv
from .torsiograph import (OrderTrack, TorsiographResult, instantaneous_speed, order_track, run_torsiograph,
                          tooth_errors, twist)
from .uff import MeasuredFunction, read_uff58, write_uff58

__all__ = ["MeasuredFunction", "read_uff58", "write_uff58", "read_curve_csv", "read_order_cut_csv",
           "read_edges_csv", "instantaneous_speed", "tooth_errors", "order_track", "twist", "run_torsiograph",
           "OrderTrack", "TorsiographResult", "frf_matrix", "estimate_modes", "run_modal_fit", "mac",
           "ModalEstimate", "MeasuredOptions", "read_measured"]
