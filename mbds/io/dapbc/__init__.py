"""DAP_BC model folders: element records, the in-file reader and user_force compilation."""

from mbds.io.dapbc.reader import is_dapbc_folder, read_dapbc_folder
from mbds.io.dapbc.records import Body, DapbcModel, Force, Funct, Joint, Point, SourcePos, Uvector
from mbds.io.dapbc.user_force import (FORCE_FIELD_COUNT, FORCE_FIELDS, SIGNATURE, UserForceCode,
                                      compile_user_force, force_field_table, from_function, user_force_code)

__all__ = ["Body", "DapbcModel", "FORCE_FIELDS", "FORCE_FIELD_COUNT", "Force", "Funct", "Joint", "Point",
           "SIGNATURE", "SourcePos", "UserForceCode", "Uvector", "compile_user_force", "force_field_table",
           "from_function", "is_dapbc_folder", "read_dapbc_folder", "user_force_code"]
