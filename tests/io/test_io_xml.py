"""XmlDoc/XmlNode through the API generated code calls: EX-34..EX-41 and the error rules of D0 §18.6."""

from __future__ import annotations

import pytest

from gplrt.io.files import StreamWriter
from gplrt.io.flashroot import FlashRoot
from gplrt.io.xmldoc import XmlDoc, XmlNode
from gplrt.lang.errors import GplException

EX34 = '<?xml version="1.0"?>\n<procedureControl cellId="TestCell">\n  <command>start</command>\n</procedureControl>\n'

EX37 = """<?xml version="1.0"?>
<procedureControl cellId="TestCell">
  <command>start</command>
  <procedure jobId="090507001" name="INS">
    <type>protocol</type>
    <testSet>INS_#_090507001</testSet>
    <index>0</index>
  </procedure>
</procedureControl>
"""


def write(path: str, text: str) -> None:
    w = StreamWriter(path)
    w.Write(text)
    w.Close()


def xml_read_file(file: str, console: list[str]) -> XmlDoc:
    """EX-35 XmlReadFile, as generated code would run it."""
    doc = XmlDoc.LoadFile(file)
    if doc.ErrorCode != 0:
        console.append("Input error " + str(doc.ErrorCode) + ", " + doc.Message)
        exc = GplException()
        exc.ErrorCode = doc.ErrorCode
        raise exc
    return doc


def xml_write_file(file: str, doc: XmlDoc, console: list[str]) -> None:
    """EX-36 XmlWriteFile."""
    try:
        doc.SaveFile(file)
    except GplException:
        if doc.ErrorCode != 0:
            console.append("Output error " + str(doc.ErrorCode) + ", " + doc.Message)
        raise


def xml_parse(doc: XmlDoc) -> list[str]:
    """EX-38 XmlParse; returns the console lines."""
    out = []
    root = doc.DocumentElement()
    command = root.GetElementNode("command")
    procedure = root.GetElementNode("procedure")
    out.append("cellId = " + root.GetAttribute("cellId"))
    out.append("command = " + command.Value)
    out.append("jobId = " + procedure.GetAttribute("jobId"))
    out.append("type = " + procedure.GetElement("type"))
    out.append("typeSet = " + procedure.GetElement("testSet"))
    return out


def xml_search_tree(node: XmlNode, name: str, console: list[str]) -> XmlNode | None:
    """EX-40 XmlSearchTree (the ByRef `found` becomes the return value here)."""
    if node.Name == name and node.Type == "element":
        console.append("Found " + name)
        return node
    child = node.FirstChild()
    while child is not None:
        found = xml_search_tree(child, name, console)
        if found is not None:
            return found
        child = child.NextSibling()
    return None


def xml_create() -> XmlDoc:
    """EX-41 XmlCreate."""
    doc = XmlDoc("procedureControl")
    root = doc.DocumentElement()
    root.AddAttribute("cellId", "TestCell")
    root.AddElement("command", "start")
    elem = root.AddElementNode("procedure")
    elem.AddAttribute("jobId", "090507001")
    elem.AddAttribute("name", "INS")
    elem.AddElement("type", "protocol")
    elem.AddElement("testSet", "INS_#_090507001")
    elem.AddElement("index", "0")
    return doc


def test_ex34_ex35_read_modify_ex36_write(flash: FlashRoot) -> None:
    write("/flash/control.xml", EX34)
    console: list[str] = []
    doc = xml_read_file("/flash/control.xml", console)
    assert console == [] and doc.ErrorCode == 0 and doc.Message == ""
    root = doc.DocumentElement()
    assert (root.Name, root.Type, root.GetAttribute("cellId")) == ("procedureControl", "element", "TestCell")
    assert root.GetElement("command") == "start"
    root.SetElement("command", "stop")
    root.SetAttribute("cellId", "Cell2")
    root.AddElement("speed", "50")
    xml_write_file("/flash/out.xml", doc, console)
    saved = (flash.root / "flash" / "out.xml").read_text()
    assert saved == (
        '<?xml version="1.0"?>\n<procedureControl cellId="Cell2">\n  <command>stop</command>\n'
        "</procedureControl>\n"
    ).replace("</procedureControl>", "<speed>50</speed></procedureControl>")
    again = xml_read_file("/flash/out.xml", console)
    assert again.DocumentElement().GetElement("command") == "stop"
    assert again.DocumentElement().GetElement("speed") == "50"


def test_unchanged_document_saves_back_identically(flash: FlashRoot) -> None:
    write("/flash/a.xml", EX37)
    doc = XmlDoc.LoadFile("/flash/a.xml")
    assert doc.SaveString() == EX37


def test_ex37_ex38_ex39_documented_output() -> None:
    doc = XmlDoc.LoadString(EX37)
    assert doc.ErrorCode == 0
    assert xml_parse(doc) == [
        "cellId = TestCell",
        "command = start",
        "jobId = 090507001",
        "type = protocol",
        "typeSet = INS_#_090507001",
    ]


def test_ex40_search_finds_element_through_text_nodes() -> None:
    doc = XmlDoc.LoadString(EX37)
    console: list[str] = []
    found = xml_search_tree(doc.DocumentElement(), "testSet", console)
    assert console == ["Found testSet"]
    assert found is not None and found.Value == "INS_#_090507001"
    assert found is doc.DocumentElement().GetElementNode("procedure").GetElementNode("testSet")
    assert xml_search_tree(doc.DocumentElement(), "missing", console) is None


def test_ex41_created_tree_saves_as_ex37(flash: FlashRoot) -> None:
    doc = xml_create()
    xml_write_file("/ROMDISK/created.xml", doc, [])
    assert (flash.root / "ROMDISK" / "created.xml").read_text() == EX37
    assert xml_parse(XmlDoc.LoadFile("/ROMDISK/created.xml"))[1] == "command = start"


def test_malformed_xml_sets_error_code_instead_of_throwing(flash: FlashRoot) -> None:
    write("/flash/bad.xml", "<a><b></a>")
    console: list[str] = []
    with pytest.raises(GplException) as exc:
        xml_read_file("/flash/bad.xml", console)
    assert exc.value.ErrorCode == -799
    assert console[0].startswith("Input error -799, XML error ")
    assert "line 1" in console[0]
    doc = XmlDoc.LoadString("not xml")
    assert doc.ErrorCode == -799 and doc.DocumentElement() is None
    with pytest.raises(GplException) as exc2:
        XmlDoc.LoadFile("/flash/none.xml")
    assert exc2.value.ErrorCode == -508


def test_navigation_counts_and_node_kinds() -> None:
    doc = XmlDoc.LoadString('<r a="1"><!--c--><x>t<![CDATA[<raw>]]></x><?pi data?></r>')
    root = doc.DocumentElement()
    assert root.ChildNodeCount == 3 and root.HasChildNodes  # attributes are not counted
    kinds = []
    child = root.FirstChild()
    while child is not None:
        kinds.append((child.Type, child.Name))
        child = child.NextSibling()
    assert kinds == [("comment", "comment"), ("element", "x"), ("pi", "pi")]
    x = root.GetElementNode("x")
    assert x.Value == "t<raw>"
    assert x.ParentNode() is root and root.ParentNode() is None
    assert root.LastChild().PreviousSibling() is x
    attr = root.GetAttributeNode("a")
    assert (attr.Type, attr.Name, attr.Value) == ("attribute", "a", "1")
    assert attr.ParentNode() is root
    assert root.GetAttributeNode("zz") is None and root.GetElementNode("zz") is None
    assert root.HasAttribute("a") and not root.HasElement("zz") and root.OwnerDocument() is doc


def test_missing_names_and_wrong_types_throw() -> None:
    root = xml_create().DocumentElement()
    for call in (
        lambda: root.GetAttribute("nope"),
        lambda: root.GetElement("nope"),
        lambda: root.SetAttribute("nope", "1"),
        lambda: root.SetElement("nope", "1"),
        lambda: root.RemoveElement("nope"),
    ):
        with pytest.raises(GplException) as exc:
            call()
        assert exc.value.ErrorCode == -802
    text = root.GetElementNode("command").FirstChild()
    assert text.Type == "text"
    with pytest.raises(GplException) as exc:
        text.AddElement("x")
    assert exc.value.ErrorCode == -803
    with pytest.raises(GplException) as exc:
        xml_create().CreateNode("bogus", "x")
    assert exc.value.ErrorCode == -803


def test_removed_nodes_raise_no_xml_node() -> None:
    doc = xml_create()
    root = doc.DocumentElement()
    procedure = root.GetElementNode("procedure")
    type_node = procedure.GetElementNode("type")
    root.RemoveChild(procedure)
    for call in (lambda: procedure.Name, lambda: type_node.Value, lambda: type_node.NextSibling()):
        with pytest.raises(GplException) as exc:
            call()
        assert exc.value.ErrorCode == -801
    command = root.GetElementNode("command")
    root.RemoveElement("command")
    with pytest.raises(GplException) as exc:
        command.Value
    assert exc.value.ErrorCode == -801
    assert root.ChildNodeCount == 0
    with pytest.raises(GplException) as exc:
        XmlNode().Name  # New XmlNode: bound to nothing
    assert exc.value.ErrorCode == -801


def test_create_insert_replace_clone_and_text_merge() -> None:
    doc = XmlDoc("root")
    root = doc.DocumentElement()
    a = doc.CreateNode("element", "a")
    assert a.Name == "a"  # a new node is valid before insertion
    root.AppendChild(a)
    b = doc.CreateNode("element", "b")
    root.InsertBefore(b, a)
    c = doc.CreateNode("element", "c")
    root.InsertAfter(c, b)
    names = [root.FirstChild().Name, root.FirstChild().NextSibling().Name, root.LastChild().Name]
    assert names == ["b", "c", "a"]
    d = doc.CreateNode("element", "d")
    root.ReplaceChild(d, c)
    with pytest.raises(GplException) as exc:
        c.Name
    assert exc.value.ErrorCode == -801
    a.AppendChild(doc.CreateNode("text", "x"))
    a.AppendChild(doc.CreateNode("text", "y"))
    assert a.ChildNodeCount == 1 and a.Value == "xy"  # adjacent text nodes merged
    attr = doc.CreateNode("attribute", "k")
    attr.Value = "v"
    a.AppendChild(attr)
    assert a.GetAttribute("k") == "v"
    copy = a.Clone(True)
    root.AppendChild(copy)
    assert copy.Value == "xy" and copy.GetAttribute("k") == "v" and copy is not a
    shallow = a.Clone()
    assert shallow.ChildNodeCount == 0
    other = XmlDoc("other")
    with pytest.raises(GplException) as exc:
        other.DocumentElement().AppendChild(a)
    assert exc.value.ErrorCode == -804
    imported = a.Clone(True, other)
    other.DocumentElement().AppendChild(imported)
    assert other.SaveString() == '<?xml version="1.0"?>\n<other>\n  <a k="v">xy</a>\n</other>\n'
    with pytest.raises(GplException):
        a.AppendChild(root)  # a node cannot contain its ancestor
    a.Value = "new"
    a.RemoveAttribute("k")
    assert doc.SaveString() == (
        '<?xml version="1.0"?>\n<root>\n  <b/>\n  <d/>\n  <a>new</a>\n  <a k="v">xy</a>\n</root>\n'
    )


def test_entities_and_save_string_byref(cell: type) -> None:
    assert XmlDoc.EncodeEntities("a<b & \"c\" 'd'>") == "a&lt;b &amp; &quot;c&quot; &apos;d&apos;&gt;"
    assert XmlDoc.DecodeEntities("a&lt;b &amp; &#65;&#x42;") == "a<b & AB"
    doc = XmlDoc("r")
    doc.DocumentElement().AddElement("v", "1 < 2 & 3")
    holder = cell("")
    doc.SaveString(holder)
    assert holder.get() == '<?xml version="1.0"?>\n<r>\n  <v>1 &lt; 2 &amp; 3</v>\n</r>\n'
    assert XmlDoc.LoadString(holder.get()).DocumentElement().GetElement("v") == "1 < 2 & 3"


def test_utf8_text_crosses_as_bytes() -> None:
    doc = XmlDoc.LoadString('<r>caf\u00c3\u00a9</r>')  # the GPL String holds UTF-8 bytes of "café"
    value = doc.DocumentElement().Value
    assert value == "caf\u00c3\u00a9"
    assert value.encode("latin-1").decode("utf-8") == "café"
