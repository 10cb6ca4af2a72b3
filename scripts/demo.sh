#!/usr/bin/env bash
# Checks the sample project end to end; sets up .venv first if needed.
source "$(dirname "$0")/_venv.sh"
gpl2py check samples/tcp_command_server
