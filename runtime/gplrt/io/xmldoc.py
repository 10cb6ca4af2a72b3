"""GPL XML classes ``XmlDoc`` and ``XmlNode`` (D0 §18), on ``xml.dom.minidom``.

Why minidom (not ElementTree): GPL exposes a DOM — text, comment, CDATA and processing-instruction
nodes are children in document order, ``NextSibling``/``PreviousSibling``/``ParentNode`` navigate
them, and attributes are nodes of their own.  minidom keeps all of that (ElementTree folds text into
``.text``/``.tail`` and has no parent links).

Decisions (the GPL Dictionary pages are not available; gpl-classes.md §18 and §23.21):

* **Children** are the non-attribute nodes, including whitespace text nodes kept by the parser
  (libxml2's default), so ``FirstChild``/``NextSibling`` visit them; ``ChildNodeCount`` counts them.
* **Name/Type**: element -> tag and ``"element"``; attribute -> name and ``"attribute"``; text ->
  ``"text"``; CDATA -> ``"cdata"``; comment -> ``"comment"``; PI -> target and ``"pi"``; document ->
  ``"document"``.  ``CreateNode`` takes the same type words.
* **Value** of an element is the concatenated text below it (EX-38: ``command.Value`` = ``start``);
  assigning it replaces the element's children by one text node.
* **Errors** (D0:5212-5237): ``LoadFile``/``LoadString`` never throw for malformed XML — they return
  an XmlDoc whose ``ErrorCode`` is -799 and whose ``Message`` carries the parser's secondary error
  number, line and column.  A missing file throws -508 (a file-system error, not XML).  Members that
  return a node return ``Nothing`` when the name is missing; other members throw -802 *Undefined XML
  name*.  A node of another document -> -804; the wrong node type -> -803; an XmlNode whose node was
  removed from the tree -> -801 *No XML node*.
* **Entities**: the parser decodes them and the writer escapes ``& < >`` (and ``"`` in attributes),
  so the output is always well-formed; ``EncodeEntities``/``DecodeEntities`` are plain string
  functions for programs that follow the manual's advice to encode data themselves.
* **Output** is ``<?xml version="1.0"?>`` then the tree; an element whose children are all elements
  is indented by two spaces per level (as libxml2's formatted save), mixed content is written as is.
  So EX-41's tree saves to exactly EX-37's text, and a loaded file saves back unchanged.
* **Characters**: XML outside is UTF-8 (D0:4916-4920); a GPL String holds bytes, so text crosses as
  UTF-8 bytes (plain ASCII is unchanged).
"""

from __future__ import annotations

import re
import xml.dom.minidom as minidom
from xml.dom import Node
from xml.parsers.expat import ExpatError

from gplrt.io.flashroot import DeviceKind, resolve
from gplrt.lang.errors import (
    CANT_OPEN_FOR_WRITE,
    DOCUMENTS_DO_NOT_MATCH,
    FILE_NOT_FOUND,
    INVALID_ARGUMENT,
    INVALID_FILE_TYPE,
    INVALID_NODE_TYPE,
    NOTHING_VALUE,
    NO_XML_NODE,
    READ_ERROR,
    UNDEFINED_XML_NAME,
    XML_ERROR,
    GplException,
    host_reason,
)
from gplrt.lang.gpltypes import Boolean, Integer, Ref, String


_TYPE_NAMES = {
    Node.ELEMENT_NODE: "element",
    Node.ATTRIBUTE_NODE: "attribute",
    Node.TEXT_NODE: "text",
    Node.CDATA_SECTION_NODE: "cdata",
    Node.COMMENT_NODE: "comment",
    Node.PROCESSING_INSTRUCTION_NODE: "pi",
    Node.DOCUMENT_NODE: "document",
}
_CHILD_TYPES = (Node.ELEMENT_NODE, Node.TEXT_NODE, Node.CDATA_SECTION_NODE, Node.COMMENT_NODE,
                Node.PROCESSING_INSTRUCTION_NODE)


def _in(text: object) -> str:
    """GPL String (bytes as characters) -> Python text, reading the bytes as UTF-8."""
    raw = str(text).encode("latin-1", errors="replace")
    try:
        return raw.decode("utf-8")
    except UnicodeDecodeError:
        return raw.decode("latin-1")


def _out(text: str) -> String:
    """Python text -> GPL String holding its UTF-8 bytes."""
    return String(text.encode("utf-8").decode("latin-1"))


def _escape(text: str, attribute: bool = False) -> str:
    text = text.replace("&", "&amp;").replace("<", "&lt;").replace(">", "&gt;")
    return text.replace('"', "&quot;") if attribute else text


class XmlDoc:
    """``New XmlDoc(root_name)``: a document whose document element is ``root_name``.

    ``New XmlDoc`` without a name gives an empty document (``LoadFile``/``LoadString`` fill one).
    """

    def __init__(self, root_name: String = String("")) -> None:
        self._dom = minidom.getDOMImplementation().createDocument(None, None, None)
        self._error = 0
        self._message = ""
        self._wrappers: dict[int, tuple[Node, XmlNode]] = {}
        self._detached: dict[int, Node] = {}  # created, not yet inserted: still valid
        if root_name:
            self._dom.appendChild(self._dom.createElement(_in(root_name)))

    # -- Shared members --------------------------------------------------------------------------

    @staticmethod
    def LoadFile(input_file: String, options: Integer = Integer(0)) -> XmlDoc:
        """Parse a file; test ``ErrorCode`` afterwards (malformed XML does not throw)."""
        cp = resolve(input_file)
        if cp.file is None or cp.kind is DeviceKind.SERIAL:
            raise GplException(INVALID_FILE_TYPE, detail=f"{input_file!r} is a device")
        try:
            data = cp.file.read_bytes()  # links and special files: -208 / -521 (sandbox.py)
        except (FileNotFoundError, NotADirectoryError, IsADirectoryError):
            raise GplException(FILE_NOT_FOUND, detail=input_file) from None
        except OSError as exc:
            raise GplException(READ_ERROR, detail=f"{input_file}: {host_reason(exc)}") from None
        return XmlDoc._parse(data)

    @staticmethod
    def LoadString(input_string: String, options: Integer = Integer(0)) -> XmlDoc:
        """Parse XML text held in a String; test ``ErrorCode`` afterwards."""
        return XmlDoc._parse(str(input_string).encode("latin-1", errors="replace"))

    @staticmethod
    def _parse(data: bytes) -> XmlDoc:
        doc = XmlDoc()
        try:
            doc._dom = minidom.parseString(data)
        except ExpatError as exc:
            doc._error = XML_ERROR
            doc._message = f"XML error {exc.code} at line {exc.lineno}, column {exc.offset + 1}: " + (
                str(exc).split(":")[0]
            )
        return doc

    @staticmethod
    def EncodeEntities(value: String) -> String:
        """Replace ``& < > " '`` by their XML entities."""
        text = _escape(str(value), attribute=True)
        return String(text.replace("'", "&apos;"))

    @staticmethod
    def DecodeEntities(value: String) -> String:
        """Replace XML entities (named, ``&#n;``, ``&#xh;``) by their characters."""

        def one(match: re.Match[str]) -> str:
            name = match.group(1)
            named = {"amp": "&", "lt": "<", "gt": ">", "quot": '"', "apos": "'"}
            if name in named:
                return named[name]
            code = int(name[2:], 16) if name[:2].lower() == "#x" else int(name[1:])
            return _out(chr(code)) if code > 255 else chr(code)

        return String(re.sub(r"&(amp|lt|gt|quot|apos|#[0-9]+|#[xX][0-9a-fA-F]+);", one, str(value)))

    # -- document members ----------------------------------------------------------------------

    @property
    def ErrorCode(self) -> Integer:
        """Code of the last major operation's error (0 = none)."""
        return Integer(self._error)

    @property
    def Message(self) -> String:
        """Detailed text of the last major operation's error ("" = none)."""
        return String(self._message)

    def DocumentElement(self) -> XmlNode | None:
        """The root element, or ``Nothing`` for an empty document."""
        root = self._dom.documentElement
        return self._wrap(root) if root is not None else None

    def CreateNode(self, type: String, name: String = String("")) -> XmlNode:
        """A new node of this document (``"element"``, ``"attribute"``, ``"text"``, ``"cdata"``,
        ``"comment"``, ``"pi"``), to be inserted with AppendChild/InsertBefore/...; for text-like
        nodes ``name`` is their initial value."""
        kind = str(type).lower()
        n = _in(name)
        dom = self._dom
        makers = {
            "element": lambda: dom.createElement(n),
            "attribute": lambda: dom.createAttribute(n),
            "text": lambda: dom.createTextNode(n),
            "cdata": lambda: dom.createCDATASection(n),
            "comment": lambda: dom.createComment(n),
            "pi": lambda: dom.createProcessingInstruction(n, ""),
        }
        if kind not in makers:
            raise GplException(INVALID_NODE_TYPE, detail=f"CreateNode type {type!r}")
        if kind in ("element", "attribute", "pi") and not n:
            raise GplException(UNDEFINED_XML_NAME, detail=f"CreateNode {kind} needs a name")
        node = makers[kind]()
        self._detached[id(node)] = node
        return self._wrap(node)

    def SaveString(self, output_string: Ref[String] | None = None, options: Integer = Integer(0)) -> String:
        """The document as XML text (also stored in ``output_string`` when one is passed)."""
        text = _out(self._serialize())
        self._error, self._message = 0, ""
        if output_string is not None:
            output_string.set(text)
        return text

    def SaveFile(self, output_file: String, options: Integer = Integer(0)) -> None:
        """Write the document as XML text to a controller file."""
        cp = resolve(output_file)
        if cp.file is None or cp.kind is not DeviceKind.DISK:
            raise GplException(CANT_OPEN_FOR_WRITE, detail=f"{output_file!r}: not a disk file")
        try:
            cp.file.write_bytes(self._serialize().encode("utf-8"))
        except OSError as exc:  # no folder, a folder of that name, the disk refused
            self._error, self._message = CANT_OPEN_FOR_WRITE, f"cannot create {output_file}"
            raise GplException(CANT_OPEN_FOR_WRITE, detail=f"{output_file}: {host_reason(exc)}") from None
        self._error, self._message = 0, ""

    # -- Python side -----------------------------------------------------------------------------

    def _wrap(self, node: Node) -> XmlNode:
        """One XmlNode per DOM node, so GPL's ``Is`` compares nodes."""
        entry = self._wrappers.get(id(node))
        if entry is not None and entry[0] is node:
            return entry[1]
        wrapper = XmlNode(_owner=self, _node=node)
        self._wrappers[id(node)] = (node, wrapper)
        return wrapper

    def _serialize(self) -> str:
        parts = ['<?xml version="1.0"?>\n']
        for child in self._dom.childNodes:
            _write(child, parts, 0, True)
            parts.append("\n")
        return "".join(parts)


def _write(node: Node, out: list[str], depth: int, fmt: bool) -> None:
    """Serialise ``node``; ``fmt`` = indent children (only when no text is mixed in)."""
    kind = node.nodeType
    if kind == Node.TEXT_NODE:
        out.append(_escape(node.data))
    elif kind == Node.CDATA_SECTION_NODE:
        out.append(f"<![CDATA[{node.data}]]>")
    elif kind == Node.COMMENT_NODE:
        out.append(f"<!--{node.data}-->")
    elif kind == Node.PROCESSING_INSTRUCTION_NODE:
        out.append(f"<?{node.target} {node.data}?>" if node.data else f"<?{node.target}?>")
    elif kind == Node.ELEMENT_NODE:
        attrs = "".join(f' {a.name}="{_escape(a.value, True)}"' for a in node.attributes.values())
        children = node.childNodes
        if not children:
            out.append(f"<{node.tagName}{attrs}/>")
            return
        out.append(f"<{node.tagName}{attrs}>")
        indent = fmt and all(
            c.nodeType in (Node.ELEMENT_NODE, Node.COMMENT_NODE, Node.PROCESSING_INSTRUCTION_NODE)
            for c in children
        )
        for child in children:
            if indent:
                out.append("\n" + "  " * (depth + 1))
            _write(child, out, depth + 1, indent)
        if indent:
            out.append("\n" + "  " * depth)
        out.append(f"</{node.tagName}>")


class XmlNode:
    """A node of an XmlDoc tree.  Obtained from ``DocumentElement``, navigation and ``Add...``
    members; ``New XmlNode`` gives an object bound to no node (its members raise -801)."""

    def __init__(self, *, _owner: XmlDoc | None = None, _node: Node | None = None) -> None:
        self._owner = _owner
        self._node = _node

    # -- validity ------------------------------------------------------------------------------

    def _live(self) -> Node:
        """The DOM node, if it is still part of its document (or a not-yet-inserted new node)."""
        node, doc = self._node, self._owner
        if node is None or doc is None:
            raise GplException(NO_XML_NODE, detail="XmlNode not bound to a node")
        top = node
        while True:
            parent = top.ownerElement if top.nodeType == Node.ATTRIBUTE_NODE else top.parentNode
            if parent is None:
                break
            top = parent
        if top is not doc._dom and doc._detached.get(id(top)) is not top:
            raise GplException(NO_XML_NODE, detail="the node was removed from its document")
        return node

    def _element(self) -> Node:
        node = self._live()
        if node.nodeType != Node.ELEMENT_NODE:
            raise GplException(INVALID_NODE_TYPE, detail=f"{_TYPE_NAMES.get(node.nodeType)} node is not an element")
        return node

    def _other(self, other: XmlNode | None, what: str) -> Node:
        if other is None:
            raise GplException(NOTHING_VALUE, detail=f"{what} is Nothing")
        node = other._live()
        if other._owner is not self._owner:
            raise GplException(DOCUMENTS_DO_NOT_MATCH, detail=f"{what} belongs to another XmlDoc")
        return node

    def _wrap(self, node: Node | None) -> XmlNode | None:
        assert self._owner is not None
        return self._owner._wrap(node) if node is not None else None

    def _child_element(self, name: str) -> Node | None:
        wanted = _in(name)
        for child in self._element().childNodes:
            if child.nodeType == Node.ELEMENT_NODE and child.tagName == wanted:
                return child
        return None

    def _insert(self, new: XmlNode, ref: XmlNode | None, after: bool) -> None:
        parent = self._live()
        node = self._other(new, "new_child")
        assert self._owner is not None
        if node.nodeType == Node.ATTRIBUTE_NODE:
            self._element().setAttributeNode(node)
        else:
            if parent.nodeType not in (Node.ELEMENT_NODE, Node.DOCUMENT_NODE):
                raise GplException(INVALID_NODE_TYPE, detail="only elements have children")
            if node is parent or _is_ancestor(node, parent):
                raise GplException(INVALID_ARGUMENT, detail="a node cannot become its own descendant")
            if ref is None:
                parent.appendChild(node)
            else:
                ref_node = self._other(ref, "ref_child")
                if ref_node.parentNode is not parent:
                    raise GplException(UNDEFINED_XML_NAME, detail="ref_child is not a child of this node")
                following = ref_node.nextSibling if after else ref_node
                if following is None:
                    parent.appendChild(node)
                else:
                    parent.insertBefore(node, following)
            _merge_text(node)
        self._owner._detached.pop(id(node), None)

    def _drop(self, node: Node) -> None:
        """Remove ``node`` (and so its subtree) from this element: their XmlNodes become invalid."""
        self._live().removeChild(node)

    # -- navigation ----------------------------------------------------------------------------

    def FirstChild(self) -> XmlNode | None:
        return self._wrap(self._live().firstChild)

    def LastChild(self) -> XmlNode | None:
        return self._wrap(self._live().lastChild)

    def NextSibling(self) -> XmlNode | None:
        return self._wrap(self._live().nextSibling)

    def PreviousSibling(self) -> XmlNode | None:
        return self._wrap(self._live().previousSibling)

    def ParentNode(self) -> XmlNode | None:
        """The parent element (for an attribute: its element; the root's parent is Nothing)."""
        node = self._live()
        parent = node.ownerElement if node.nodeType == Node.ATTRIBUTE_NODE else node.parentNode
        if parent is None or parent.nodeType == Node.DOCUMENT_NODE:
            return None
        return self._wrap(parent)

    def OwnerDocument(self) -> XmlDoc:
        self._live()
        assert self._owner is not None
        return self._owner

    @property
    def ChildNodeCount(self) -> Integer:
        """Number of non-attribute children."""
        return Integer(len(self._live().childNodes))

    @property
    def HasChildNodes(self) -> Boolean:
        return Boolean(len(self._live().childNodes) > 0)

    @property
    def Name(self) -> String:
        node = self._live()
        if node.nodeType in (Node.ELEMENT_NODE, Node.ATTRIBUTE_NODE):
            return _out(node.nodeName)
        if node.nodeType == Node.PROCESSING_INSTRUCTION_NODE:
            return _out(node.target)
        return String(_TYPE_NAMES[node.nodeType])

    @property
    def Type(self) -> String:
        return String(_TYPE_NAMES[self._live().nodeType])

    @property
    def Value(self) -> String:
        """Text of the node; for an element the concatenated text below it (EX-38)."""
        node = self._live()
        if node.nodeType == Node.ATTRIBUTE_NODE:
            return _out(node.value)
        if node.nodeType in (Node.ELEMENT_NODE,):
            return _out(_text_of(node))
        if node.nodeType == Node.DOCUMENT_NODE:
            return String("")
        return _out(node.data)

    @Value.setter
    def Value(self, value: String) -> None:
        node = self._live()
        text = _in(value)
        if node.nodeType == Node.ATTRIBUTE_NODE:
            node.value = text
        elif node.nodeType == Node.ELEMENT_NODE:
            for child in list(node.childNodes):
                node.removeChild(child)
            if text:
                node.appendChild(node.ownerDocument.createTextNode(text))
        elif node.nodeType == Node.DOCUMENT_NODE:
            raise GplException(INVALID_NODE_TYPE, detail="a document has no value")
        else:
            node.data = text

    # -- attributes ----------------------------------------------------------------------------

    def AddAttribute(self, name: String, value: String) -> None:
        """Add (or overwrite) an attribute of this element."""
        self._element().setAttribute(_in(name), _in(value))

    def GetAttribute(self, name: String) -> String:
        element = self._element()
        if not element.hasAttribute(_in(name)):
            raise GplException(UNDEFINED_XML_NAME, detail=f"no attribute {name!r}")
        return _out(element.getAttribute(_in(name)))

    def GetAttributeNode(self, name: String) -> XmlNode | None:
        node = self._live()
        if node.nodeType != Node.ELEMENT_NODE:
            return None
        return self._wrap(node.getAttributeNode(_in(name)))

    def HasAttribute(self, name: String) -> Boolean:
        return Boolean(self._element().hasAttribute(_in(name)))

    def SetAttribute(self, name: String, value: String) -> None:
        """Change the value of an **existing** attribute."""
        element = self._element()
        if not element.hasAttribute(_in(name)):
            raise GplException(UNDEFINED_XML_NAME, detail=f"no attribute {name!r}")
        element.setAttribute(_in(name), _in(value))

    def RemoveAttribute(self, name: String) -> None:
        element = self._element()
        if not element.hasAttribute(_in(name)):
            raise GplException(UNDEFINED_XML_NAME, detail=f"no attribute {name!r}")
        element.removeAttribute(_in(name))

    # -- child elements ------------------------------------------------------------------------

    def AddElement(self, name: String, value: String | None = None) -> None:
        """Add a child element, with a text value if given."""
        self.AddElementNode(name, value)

    def AddElementNode(self, name: String, value: String | None = None) -> XmlNode:
        """Add a child element (with optional text value) and return it."""
        element = self._element()
        child = element.ownerDocument.createElement(_in(name))
        if value is not None and str(value) != "":
            child.appendChild(element.ownerDocument.createTextNode(_in(value)))
        element.appendChild(child)
        result = self._wrap(child)
        assert result is not None
        return result

    def GetElement(self, name: String) -> String:
        """Text value of the first child element called ``name``."""
        child = self._child_element(name)
        if child is None:
            raise GplException(UNDEFINED_XML_NAME, detail=f"no element {name!r}")
        return _out(_text_of(child))

    def GetElementNode(self, name: String) -> XmlNode | None:
        """The first child element called ``name``, or Nothing."""
        if self._live().nodeType != Node.ELEMENT_NODE:
            return None
        return self._wrap(self._child_element(name))

    def HasElement(self, name: String) -> Boolean:
        return Boolean(self._child_element(name) is not None)

    def SetElement(self, name: String, value: String) -> None:
        """Change the text value of an **existing** child element."""
        child = self._child_element(name)
        if child is None:
            raise GplException(UNDEFINED_XML_NAME, detail=f"no element {name!r}")
        assert self._owner is not None
        self._owner._wrap(child).Value = value

    def RemoveElement(self, name: String) -> None:
        """Remove the first child element called ``name`` with its subtree."""
        child = self._child_element(name)
        if child is None:
            raise GplException(UNDEFINED_XML_NAME, detail=f"no element {name!r}")
        self._drop(child)

    # -- tree editing --------------------------------------------------------------------------

    def AppendChild(self, new_node: XmlNode) -> None:
        """Add as the last child (adjacent text nodes merge); an attribute node becomes an attribute."""
        self._insert(new_node, None, after=False)

    def InsertBefore(self, new_child: XmlNode, ref_child: XmlNode) -> None:
        self._insert(new_child, ref_child, after=False)

    def InsertAfter(self, new_child: XmlNode, ref_child: XmlNode) -> None:
        self._insert(new_child, ref_child, after=True)

    def RemoveChild(self, old_child: XmlNode) -> None:
        """Remove a child with its subtree; XmlNodes referring into it then raise -801."""
        node = self._other(old_child, "old_child")
        parent = self._live()
        if node.nodeType == Node.ATTRIBUTE_NODE and node.ownerElement is parent:
            parent.removeAttributeNode(node)
            return
        if node.parentNode is not parent:
            raise GplException(UNDEFINED_XML_NAME, detail="old_child is not a child of this node")
        self._drop(node)

    def ReplaceChild(self, new_child: XmlNode, old_child: XmlNode) -> None:
        old = self._other(old_child, "old_child")
        if old.parentNode is not self._live():
            raise GplException(UNDEFINED_XML_NAME, detail="old_child is not a child of this node")
        self._insert(new_child, old_child, after=False)
        self._drop(old)

    def Clone(self, deep: Boolean = Boolean(False), xmldoc: XmlDoc | None = None) -> XmlNode:
        """A copy of this node (with its subtree if ``deep``), for this or another document."""
        node = self._live()
        target = xmldoc if xmldoc is not None else self._owner
        assert target is not None
        if node.nodeType == Node.DOCUMENT_NODE:
            raise GplException(INVALID_NODE_TYPE, detail="cannot clone a document node")
        copy = target._dom.importNode(node, bool(deep))
        target._detached[id(copy)] = copy
        return target._wrap(copy)

    def __repr__(self) -> str:
        node = self._node
        return f"<XmlNode {getattr(node, 'nodeName', None)!r}>"


def _text_of(node: Node) -> str:
    if node.nodeType in (Node.TEXT_NODE, Node.CDATA_SECTION_NODE):
        return node.data
    return "".join(_text_of(c) for c in node.childNodes if c.nodeType in _CHILD_TYPES[:3] or c.nodeType == Node.ELEMENT_NODE)


def _is_ancestor(candidate: Node, node: Node) -> bool:
    parent = node.parentNode
    while parent is not None:
        if parent is candidate:
            return True
        parent = parent.parentNode
    return False


def _merge_text(node: Node) -> None:
    """Merge a just-inserted text node with adjacent text siblings (D0:5013, 5043-5046)."""
    if node.nodeType != Node.TEXT_NODE or node.parentNode is None:
        return
    for neighbour in (node.previousSibling, node.nextSibling):
        if neighbour is not None and neighbour.nodeType == Node.TEXT_NODE:
            if neighbour is node.previousSibling:
                neighbour.data += node.data
                node.parentNode.removeChild(node)
                node = neighbour
            else:
                node.data += neighbour.data
                node.parentNode.removeChild(neighbour)


__all__ = ["XmlDoc", "XmlNode"]
