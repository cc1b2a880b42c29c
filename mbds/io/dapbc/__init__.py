"""DAP_BC model folders: element records, the in-file reader and user_force compilation."""
