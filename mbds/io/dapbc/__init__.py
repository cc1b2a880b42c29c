"""DAP_BC model folders: element records, the in-file reader and user_force compilation."""

from mbds.io.dapbc.reader import is_dapbc_folder, read_dapbc_folder
from mbds.io.dapbc.records import Body, DapbcModel, Force, Funct, Joint, Point, SourcePos, Uvector

__all__ = ["Body", "DapbcModel", "Force", "Funct", "Joint", "Point", "SourcePos", "Uvector",
           "is_dapbc_folder", "read_dapbc_folder"]
