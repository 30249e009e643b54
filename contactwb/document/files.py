"""An assembly from a file, for the file-based tools (`contacts mesh`,
`contacts trial`, `--disassembly`): a STEP file read in C++, or a FreeCAD
document's visible solids."""
import os
import zipfile

from contactwb import core
from contactwb.core import meshes


# Limits of an .FCStd archive read (issue 25): beyond them the file is refused
# before FreeCAD unpacks it.
FCSTD_MAX_MEMBER_BYTES = 2 * 1024 ** 3   # one member, uncompressed
FCSTD_MAX_TOTAL_BYTES = 4 * 1024 ** 3    # all members
FCSTD_MAX_MEMBERS = 100_000
FCSTD_MAX_RATIO = 1000                   # uncompressed / compressed, for members above 1 MB


def check_fcstd(path):
    """A clear error for what FreeCAD would half-open or crash on, and an
    "unsupported file" refusal (exit 3) for what it must not be given: members
    encrypted, compressed other than stored or deflated, too large or
    inflating beyond FCSTD_MAX_RATIO, and a Document.xml that declares
    entities (an expansion bomb) or is not well-formed XML. Parsed with
    expat, entity declarations refused, before FreeCAD reads a byte."""
    if not zipfile.is_zipfile(path):
        raise core.InputError(f"not a FreeCAD document (not a zip archive: truncated, or another format) "
                              f"(file '{path}')")

    def unsupported(why):
        return core.InputError(f"unsupported file: {why} (file '{path}')")
    try:
        with zipfile.ZipFile(path) as archive:
            members = archive.infolist()
            if "Document.xml" not in archive.namelist():
                raise core.InputError(f"not a FreeCAD document (no Document.xml) (file '{path}')")
            if len(members) > FCSTD_MAX_MEMBERS:
                raise unsupported(f"{len(members)} archive members (at most {FCSTD_MAX_MEMBERS})")
            total = 0
            for member in members:
                if member.flag_bits & 0x1:
                    raise unsupported(f"member '{member.filename}' is encrypted")
                if member.compress_type not in (zipfile.ZIP_STORED, zipfile.ZIP_DEFLATED):
                    raise unsupported(f"member '{member.filename}' uses compression method {member.compress_type} "
                                      "(only stored and deflated are read)")
                if member.file_size > FCSTD_MAX_MEMBER_BYTES:
                    raise unsupported(f"member '{member.filename}' is {member.file_size} bytes uncompressed "
                                      f"(at most {FCSTD_MAX_MEMBER_BYTES})")
                if member.file_size > 1024 ** 2 and member.file_size > FCSTD_MAX_RATIO * max(member.compress_size, 1):
                    raise unsupported(f"member '{member.filename}' inflates {member.compress_size} bytes to "
                                      f"{member.file_size} (more than {FCSTD_MAX_RATIO} times)")
                total += member.file_size
            if total > FCSTD_MAX_TOTAL_BYTES:
                raise unsupported(f"{total} bytes uncompressed in all (at most {FCSTD_MAX_TOTAL_BYTES})")
            damaged = archive.testzip()
            if damaged:
                raise core.InputError(f"damaged FreeCAD document (member '{damaged}' is corrupt) (file '{path}')")
            check_document_xml(archive, unsupported)
    except zipfile.BadZipFile as error:
        raise core.InputError(f"damaged FreeCAD document ({error}) (file '{path}')")
    except core.ContactsError:  # ours (a RuntimeError too)
        raise
    except (NotImplementedError, RuntimeError) as error:  # zipfile: unsupported method, encrypted
        raise unsupported(str(error))


def check_document_xml(archive, unsupported):
    """Document.xml parsed in a stream by expat with no entity declarations
    allowed (none in a real document): an expansion bomb is refused before
    any expansion."""
    from xml.parsers import expat
    parser = expat.ParserCreate()

    def refuse_entity(name, *_):
        raise unsupported(f"Document.xml declares the entity '{name}' (entity declarations are refused)")
    parser.EntityDeclHandler = refuse_entity
    parser.UnparsedEntityDeclHandler = refuse_entity
    parser.SetParamEntityParsing(expat.XML_PARAM_ENTITY_PARSING_NEVER)
    try:
        with archive.open("Document.xml") as stream:
            while True:
                chunk = stream.read(1 << 20)
                parser.Parse(chunk, not chunk)
                if not chunk:
                    break
    except expat.ExpatError as error:
        raise unsupported(f"Document.xml is not well-formed XML ({error})")


def load_assembly(path, max_bodies=None):
    """The bodies of a STEP file (read in C++) or of a FreeCAD document's visible solids. A STEP
    assembly expanding to more than `max_bodies` instances (default one million) is refused."""
    if not os.path.isfile(path):
        raise core.InputError(f"no such file: '{path}'")
    if path.lower().endswith(".fcstd"):
        check_fcstd(path)
        from contactwb.document import bodies as document_bodies
        from contactwb.document import freecad_setup
        doc = freecad_setup.open_document(os.path.abspath(path))
        try:
            assembly, _ = document_bodies.assembly_from_document(doc, None, [])
        except core.InputError as error:  # a body's error (the core names body and face): the file too
            if os.path.basename(path) in str(error):
                raise
            raise core.InputError(f"{error} (file '{path}')") from error
        return assembly
    return meshes.read_step_assembly(path, max_bodies)
