"""Controller I/O services: files, XML, sockets, Modbus/TCP, serial ports and vision.

GPL classes (members in GPL spelling, see ``gplrt/CATALOGUE.md``):

* files      -- ``File`` (Shared), ``StreamReader``, ``StreamWriter``; controller paths are mapped
                into a sandbox by ``flashroot`` (``set_flash_root``) and every host operation
                walks it link-free through ``sandbox``; NVRAM by ``nvram``
* xmldoc     -- ``XmlDoc``, ``XmlNode``
* sockets    -- ``IPEndPoint``, ``Socket``, ``TcpClient``, ``TcpListener``, ``UdpClient``
* modbus     -- ``Modbus`` (MODBUS/TCP master)
* serial     -- ``/dev/comN`` back ends for the stream classes (loop-back, pseudo-terminal)
* vision     -- ``Vision``, ``VisResult`` with a pluggable simulated vision server

A session's disks and network are its own (``Session.files``, ``Session.network``:
``gplrt.session``); ``set_flash_root`` and ``configure_network`` change the current session's.
Serial ports and the vision server are devices of the process: ``configure_serial``,
``set_vision_server``.  Every wait on the outside world runs in ``_blocking``'s hook.
"""

from gplrt.io.files import File, StreamReader, StreamWriter
from gplrt.io.flashroot import FlashRoot, get_flash_root, set_flash_root
from gplrt.io.modbus import Modbus
from gplrt.io.serial import LoopbackPort, PtyPort, configure_serial
from gplrt.io.sockets import IPEndPoint, NetworkConfig, Socket, TcpClient, TcpListener, UdpClient, configure_network
from gplrt.io.vision import ScriptedVisionServer, Vision, VisionToolResult, VisResult, set_vision_server
from gplrt.io.xmldoc import XmlDoc, XmlNode

__all__ = [
    "File",
    "StreamReader",
    "StreamWriter",
    "FlashRoot",
    "get_flash_root",
    "set_flash_root",
    "Modbus",
    "LoopbackPort",
    "PtyPort",
    "configure_serial",
    "IPEndPoint",
    "NetworkConfig",
    "Socket",
    "TcpClient",
    "TcpListener",
    "UdpClient",
    "configure_network",
    "ScriptedVisionServer",
    "Vision",
    "VisionToolResult",
    "VisResult",
    "set_vision_server",
    "XmlDoc",
    "XmlNode",
]
